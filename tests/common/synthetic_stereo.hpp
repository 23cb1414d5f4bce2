#pragma once
// Random-dot and periodic stereograms with exactly known disparity, for the tests.

#include <cmath>
#include <cstdint>
#include <functional>
#include <random>
#include <vector>

#include "lidar_sgm/core/image.hpp"
#include "lidar_sgm/core/lidar_points.hpp"

namespace lidar_sgm {
namespace test {

struct SyntheticStereo {
  Image<std::uint8_t> left;
  Image<std::uint8_t> right;
  Image<float> disparity;      ///< GT for the left image [px]
  Image<std::uint8_t> occluded;  ///< 1 where the left pixel has no counterpart in the right image
};

/// A 1D-in-x texture per row: random values at integer u, linear in between. `period` > 0 makes
/// it repeat every `period` px along x (a stereo-ambiguous texture).
class RowTexture {
 public:
  RowTexture(int height, int span, int period, unsigned seed) : span_(span), period_(period) {
    std::mt19937 engine(seed);
    values_.resize(static_cast<std::size_t>(height) * span);
    for (auto& v : values_) v = static_cast<float>(engine() % 256u);
  }
  /// u may be negative (the right image sees left of the left image).
  float operator()(double u, int y) const {
    const double shifted = u + offset_;
    const auto i0 = static_cast<long>(std::floor(shifted));
    const double t = shifted - static_cast<double>(i0);
    return static_cast<float>((1.0 - t) * at(i0, y) + t * at(i0 + 1, y));
  }

 private:
  float at(long i, int y) const {
    long k = period_ > 0 ? ((i % period_) + period_) % period_ : i;
    k = std::max(0L, std::min(static_cast<long>(span_) - 1, k));
    return values_[static_cast<std::size_t>(y) * span_ + static_cast<std::size_t>(k)];
  }
  int span_;
  int period_;
  double offset_ = 256.0;
  std::vector<float> values_;
};

/// A single surface with disparity d(x, y) (left image coordinates, |dd/dx| < 1, so no
/// self-occlusion): left(x) = T(x), right(xr) = T(x) with x - d(x, y) = xr.
inline SyntheticStereo makeStereo(int width, int height, const std::function<double(double, double)>& d,
                                  int period = 0, unsigned seed = 7) {
  RowTexture texture(height, width + 512, period, seed);
  SyntheticStereo s;
  s.left = Image<std::uint8_t>(width, height);
  s.right = Image<std::uint8_t>(width, height);
  s.disparity = Image<float>(width, height);
  s.occluded = Image<std::uint8_t>(width, height);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      s.left(x, y) = static_cast<std::uint8_t>(std::lround(texture(x, y)));
      s.disparity(x, y) = static_cast<float>(d(x, y));
      s.occluded(x, y) = x - d(x, y) < 0.0 ? 1 : 0;
    }
    for (int xr = 0; xr < width; ++xr) {
      double x = xr;
      for (int it = 0; it < 50; ++it) x = xr + d(x, y);  // fixed point of x = xr + d(x, y)
      s.right(xr, y) = static_cast<std::uint8_t>(std::lround(texture(x, y)));
    }
  }
  return s;
}

/// Every `keepOneIn`-th pixel (random, seeded) of the GT as a LiDAR point, with Gaussian noise.
inline LidarPoints sampleLidar(const Image<float>& gt, double share, double noiseSigma, unsigned seed,
                               Image<std::uint8_t>* inputMask = nullptr) {
  std::mt19937 engine(seed);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  std::normal_distribution<double> noise(0.0, noiseSigma > 0 ? noiseSigma : 1.0);
  std::vector<LidarSample> samples;
  if (inputMask) *inputMask = Image<std::uint8_t>(gt.width(), gt.height());
  for (int y = 0; y < gt.height(); ++y) {
    for (int x = 0; x < gt.width(); ++x) {
      if (uniform(engine) >= share) continue;
      const double d = gt(x, y) + (noiseSigma > 0 ? noise(engine) : 0.0);
      samples.push_back({x, y, static_cast<int>(std::lround(d * kDisparityScale))});
      if (inputMask) (*inputMask)(x, y) = 1;
    }
  }
  return LidarPoints(gt.width(), gt.height(), samples);
}

}  // namespace test
}  // namespace lidar_sgm
