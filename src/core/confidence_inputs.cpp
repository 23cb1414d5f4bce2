#include "core/confidence_inputs.hpp"

#include <algorithm>
#include <cstdlib>
#include <vector>

#include "core/confidence_pixel.hpp"

namespace lidar_sgm {

void lidarDistance(ImageView<const std::uint8_t> support, ImageView<std::uint8_t> distance,
                   ConfidenceScratch& scratch) {
  const int W = support.width;
  const int H = support.height;
  const int cap = kLidarDistanceCap;
  // Separable: the vertical distance per column (two sweeps), then the Chebyshev distance
  // min over |dx| <= cap of max(|dx|, vertical(x + dx)).
  std::vector<std::uint8_t>& vertical = scratch.bytes;
  vertical.resize(static_cast<std::size_t>(W) * H);
  const auto v = [&](int x, int y) -> std::uint8_t& { return vertical[static_cast<std::size_t>(y) * W + x]; };
  // Row by row (memory order), each column's distance carried from the row before.
  for (int y = 0; y < H; ++y) {
    const std::uint8_t* s = support.row(y);
    for (int x = 0; x < W; ++x) {
      const int above = y == 0 ? cap : v(x, y - 1);
      v(x, y) = static_cast<std::uint8_t>(s[x] != 0 ? 0 : std::min(above + 1, cap));
    }
  }
  for (int y = H - 2; y >= 0; --y) {
    for (int x = 0; x < W; ++x) v(x, y) = std::min<std::uint8_t>(v(x, y), static_cast<std::uint8_t>(std::min(v(x, y + 1) + 1, cap)));
  }
  for (int y = 0; y < H; ++y) {
    // A row no support comes within `cap` rows of (above or below the scan, or no LiDAR at all)
    // is `cap` everywhere: skip the search.
    bool far = true;
    for (int x = 0; x < W && far; ++x) far = v(x, y) == cap;
    if (far) {
      std::fill(distance.row(y), distance.row(y) + W, static_cast<std::uint8_t>(cap));
      continue;
    }
    for (int x = 0; x < W; ++x) {
      int best = v(x, y);
      for (int dx = 1; dx < best; ++dx) {
        if (x - dx >= 0) best = std::min(best, std::max(dx, static_cast<int>(v(x - dx, y))));
        if (x + dx < W) best = std::min(best, std::max(dx, static_cast<int>(v(x + dx, y))));
      }
      distance(x, y) = static_cast<std::uint8_t>(best);
    }
  }
}

namespace {

template <typename T>
void textureOf(ImageView<const T> image, int shift, int saturation, ImageView<std::uint8_t> texture,
               ImageView<std::uint8_t> saturated, ConfidenceScratch& scratch) {
  const int W = image.width;
  const int H = image.height;
  // |I(x+1) - I(x-1)| (border pixels repeat), then its 5x5 sum by rows and columns.
  std::vector<int>& gradient = scratch.a;
  std::vector<int>& rowSum = scratch.b;
  gradient.resize(static_cast<std::size_t>(W) * H);
  rowSum.resize(static_cast<std::size_t>(W) * H);
  for (int y = 0; y < H; ++y) {
    for (int x = 0; x < W; ++x) {
      const int a = image(std::min(x + 1, W - 1), y);
      const int b = image(std::max(x - 1, 0), y);
      gradient[static_cast<std::size_t>(y) * W + x] = std::abs(a - b) >> shift;
      saturated(x, y) = image(x, y) >= saturation ? 1 : 0;
    }
  }
  for (int y = 0; y < H; ++y) {
    for (int x = 0; x < W; ++x) {
      int sum = 0;
      for (int dx = -2; dx <= 2; ++dx) sum += gradient[static_cast<std::size_t>(y) * W + std::clamp(x + dx, 0, W - 1)];
      rowSum[static_cast<std::size_t>(y) * W + x] = sum;
    }
  }
  for (int y = 0; y < H; ++y) {
    for (int x = 0; x < W; ++x) {
      int sum = 0;
      for (int dy = -2; dy <= 2; ++dy) sum += rowSum[static_cast<std::size_t>(std::clamp(y + dy, 0, H - 1)) * W + x];
      texture(x, y) = static_cast<std::uint8_t>(std::min((sum + 12) / 25, 255));
    }
  }
}

}  // namespace

void textureAndSaturation(const GrayImageView& image, ImageView<std::uint8_t> texture,
                          ImageView<std::uint8_t> saturated, ConfidenceScratch& scratch) {
  if (!image.gray8.empty()) {
    textureOf(image.gray8, 0, 250, texture, saturated, scratch);
  } else if (!image.gray16.empty()) {
    textureOf(image.gray16, 8, 250 << 8, texture, saturated, scratch);
  } else {
    for (int y = 0; y < texture.height; ++y) {
      std::fill(texture.row(y), texture.row(y) + texture.width, std::uint8_t{0});
      std::fill(saturated.row(y), saturated.row(y) + saturated.width, std::uint8_t{0});
    }
  }
}

void disparityRange(ImageView<const std::int16_t> disparity, ImageView<std::uint8_t> range,
                    ConfidenceScratch& scratch) {
  const int W = disparity.width;
  const int H = disparity.height;
  // Separable: min and max over 5 columns, then over 5 rows; invalid pixels take no part.
  constexpr int kNone = 1 << 20;
  std::vector<int>& rowMin = scratch.a;
  std::vector<int>& rowMax = scratch.b;
  rowMin.resize(static_cast<std::size_t>(W) * H);
  rowMax.resize(static_cast<std::size_t>(W) * H);
  for (int y = 0; y < H; ++y) {
    for (int x = 0; x < W; ++x) {
      int lo = kNone, hi = -kNone;
      for (int dx = -2; dx <= 2; ++dx) {
        if (x + dx < 0 || x + dx >= W) continue;
        const int d = disparity(x + dx, y);
        if (d == kInvalidDisparity) continue;
        lo = std::min(lo, d);
        hi = std::max(hi, d);
      }
      rowMin[static_cast<std::size_t>(y) * W + x] = lo;
      rowMax[static_cast<std::size_t>(y) * W + x] = hi;
    }
  }
  for (int y = 0; y < H; ++y) {
    for (int x = 0; x < W; ++x) {
      if (disparity(x, y) == kInvalidDisparity) {
        range(x, y) = 0;
        continue;
      }
      int lo = kNone, hi = -kNone;
      for (int dy = -2; dy <= 2; ++dy) {
        if (y + dy < 0 || y + dy >= H) continue;
        lo = std::min(lo, rowMin[static_cast<std::size_t>(y + dy) * W + x]);
        hi = std::max(hi, rowMax[static_cast<std::size_t>(y + dy) * W + x]);
      }
      range(x, y) = static_cast<std::uint8_t>(std::min((hi - lo) / kDisparityScale, kDisparityRangeCap));
    }
  }
}

ConfidencePixel confidencePixel(const ConfidenceInputs& in, MatchMode mode, int paths, int x, int y) {
  return inline_model::pixel(in, mode, paths, x, y);
}

void combineConfidence(const ConfidenceInputs& inputs, MatchMode mode, int paths,
                       ImageView<const std::int16_t> disparity, ImageView<std::uint8_t> confidence) {
  const ConfidenceModel& model = confidenceModel(mode);
  for (int y = 0; y < disparity.height; ++y) {
    for (int x = 0; x < disparity.width; ++x) {
      confidence(x, y) = disparity(x, y) == kInvalidDisparity
                             ? 0
                             : confidenceFromLogit256(confidenceLogit256(model, confidencePixel(inputs, mode, paths, x, y)));
    }
  }
}

}  // namespace lidar_sgm
