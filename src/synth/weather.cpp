#include "weather.hpp"

#include <algorithm>
#include <cmath>
#include <random>

#include "random.hpp"

namespace lidar_sgm {
namespace synth {
namespace {

std::uint8_t toByte(double value) { return static_cast<std::uint8_t>(std::clamp(std::lround(value), 0L, 255L)); }

constexpr double kNoiseSigma = 2.0;      // gray levels
constexpr double kStreakTarget = 235.0;  // a lit drop is brighter than most of the scene
constexpr double kStreakOpacity = 0.3;

}  // namespace

void addRainToImage(Image<Rgb8>& image, std::uint32_t seed) {
  std::mt19937 rng(seed);
  for (int y = 0; y < image.height(); ++y) {
    for (int x = 0; x < image.width(); ++x) {
      Rgb8& p = image(x, y);
      const double n = kNoiseSigma * gaussian(rng);  // luminance noise, as most of a sensor's
      p = {toByte(p.r + n), toByte(p.g + n), toByte(p.b + n)};
    }
  }
  const double slant = uniform(rng, 0.1, 0.3);  // wind: the same for every drop of the frame
  const int streaks = image.width() * image.height() / 1200;
  for (int s = 0; s < streaks; ++s) {
    const double x0 = uniform(rng, 0.0, image.width());
    const double y0 = uniform(rng, 0.0, image.height());
    const int length = uniformInt(rng, 8, 28);
    for (int i = 0; i < length; ++i) {
      const int x = static_cast<int>(x0 + slant * i);
      const int y = static_cast<int>(y0) + i;
      if (x < 0 || x >= image.width() || y >= image.height()) break;
      Rgb8& p = image(x, y);
      auto blend = [](std::uint8_t c) { return toByte(c + kStreakOpacity * (kStreakTarget - c)); };
      p = {blend(p.r), blend(p.g), blend(p.b)};
    }
  }
}

}  // namespace synth
}  // namespace lidar_sgm
