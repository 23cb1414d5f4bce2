// Downstream use of lidar_sgm::core from an installed package: stereo-only and LiDAR-only SGM on a
// synthetic fronto-parallel pair whose true disparity is known. Exits non-zero when the result is
// wrong, so a package that links but computes nonsense (a backend left out) fails too.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>
#include <vector>

#include <lidar_sgm/core/image.hpp>
#include <lidar_sgm/core/lidar_points.hpp>
#include <lidar_sgm/core/matcher.hpp>
#include <lidar_sgm/core/parameters.hpp>
#include <lidar_sgm/version.hpp>

namespace {

constexpr int kWidth = 256;
constexpr int kHeight = 96;
constexpr int kDisparity = 12;  // px, the whole scene

// Share of pixels right of the search range whose disparity is within 1 px of kDisparity.
double shareCorrect(const lidar_sgm::Image<std::int16_t>& disparity, int minX) {
  int correct = 0;
  int total = 0;
  for (int y = 4; y < kHeight - 4; ++y) {
    for (int x = minX; x < kWidth - 4; ++x) {
      ++total;
      const int d16 = disparity(x, y);
      if (d16 != lidar_sgm::kInvalidDisparity && std::abs(d16 - 16 * kDisparity) <= 16) ++correct;
    }
  }
  return static_cast<double>(correct) / total;
}

}  // namespace

int main() {
  if (std::strcmp(lidar_sgm::versionString(), EXPECTED_VERSION) != 0) {
    std::fprintf(stderr, "version.hpp says %s, the package %s\n", lidar_sgm::versionString(), EXPECTED_VERSION);
    return 1;
  }

  // Random texture (census needs some); right(x) = left(x + d): a left pixel x matches x - d.
  std::mt19937 random(7);
  std::uniform_int_distribution<int> gray(0, 255);
  lidar_sgm::Image<std::uint8_t> left(kWidth, kHeight);
  lidar_sgm::Image<std::uint8_t> right(kWidth, kHeight);
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < kWidth + kDisparity; ++x) {
      const auto value = static_cast<std::uint8_t>(gray(random));
      if (x < kWidth) left(x, y) = value;
      if (x - kDisparity >= 0) right(x - kDisparity, y) = value;
    }
  }

  lidar_sgm::Parameters params;
  params.numDisparities = 32;
  auto matcher = lidar_sgm::Matcher::create(lidar_sgm::Backend::Auto, params);
  lidar_sgm::Image<std::int16_t> disparity(kWidth, kHeight);

  const lidar_sgm::ImageView<const std::uint8_t> leftView = left.view();
  const lidar_sgm::ImageView<const std::uint8_t> rightView = right.view();
  matcher->compute(leftView, rightView, nullptr, disparity.view());
  const double stereo = shareCorrect(disparity, params.numDisparities);

  // LiDAR-only: one point every 4th pixel, every 4th row, at the true disparity.
  std::vector<lidar_sgm::LidarSample> samples;
  for (int y = 0; y < kHeight; y += 4) {
    for (int x = 0; x < kWidth; x += 4) samples.push_back({x, y, 16 * kDisparity});
  }
  const lidar_sgm::LidarPoints lidar(kWidth, kHeight, samples);
  matcher->compute(leftView, lidar_sgm::GrayImageView(), &lidar, disparity.view());
  const double lidarOnly = shareCorrect(disparity, 4);

  std::printf("lidar_sgm %s, backend %s: correct (1 px) stereo-only %.3f, LiDAR-only %.3f\n",
              lidar_sgm::versionString(), lidar_sgm::toString(matcher->backend()).c_str(), stereo, lidarOnly);
  if (stereo < 0.95 || lidarOnly < 0.95) {
    std::fprintf(stderr, "FAILED: expected >= 0.95 correct in both modes\n");
    return 1;
  }
  return 0;
}
