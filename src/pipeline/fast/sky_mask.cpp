// removeSky (sky_mask.cpp, the specification), fast: the same sets in row order. The texture
// test's window sums come from column sums slid down the rows (the integral image's sums, exact
// in integers), the rim's "sky within the radius" from a dilation of the sky by rows and then
// columns (the specification's integral image of the mask asks the same question); both are
// computed only for the rows that hold candidates. The row kernels are compiled for every
// instruction set Highway targets (the compiler vectorises them) and chosen at run time; rows are
// split among threads, except the flood fill from the top row: a connected component, the same
// set in any visiting order.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "pipeline/fast/sky_mask.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <stdexcept>

#include "pipeline/fast/fast_passes.hpp"
#include "pipeline/fast/parallel.hpp"

HWY_BEFORE_NAMESPACE();
namespace lidar_sgm {
namespace fast {
namespace HWY_NAMESPACE {

// The left image's row in 8-bit levels (16-bit images by their high byte).
void LevelsRow8(const std::uint8_t* HWY_RESTRICT in, int width, std::uint8_t* HWY_RESTRICT out) {
  for (int x = 0; x < width; ++x) out[x] = in[x];
}
void LevelsRow16(const std::uint16_t* HWY_RESTRICT in, int width, std::uint8_t* HWY_RESTRICT out) {
  for (int x = 0; x < width; ++x) out[x] = static_cast<std::uint8_t>(in[x] >> 8);
}

// |L(x+1) - L(x)| + |L(x, y+1) - L(x)|, each 0 at the image's last column / row (below == null).
void GradientRow(const std::uint8_t* HWY_RESTRICT level, const std::uint8_t* HWY_RESTRICT below, int width,
                 std::uint16_t* HWY_RESTRICT out) {
  for (int x = 0; x + 1 < width; ++x) out[x] = static_cast<std::uint16_t>(std::abs(level[x + 1] - level[x]));
  out[width - 1] = 0;
  if (below != nullptr) {
    for (int x = 0; x < width; ++x) out[x] = static_cast<std::uint16_t>(out[x] + std::abs(below[x] - level[x]));
  }
}

// sums += sign * row.
void AddRow(const std::uint16_t* HWY_RESTRICT row, int width, int sign, std::int32_t* HWY_RESTRICT sums) {
  for (int x = 0; x < width; ++x) sums[x] += sign * static_cast<std::int32_t>(row[x]);
}

// skyLike of one row: a candidate (y < candidateEnd) that is far (d < farLimit) or, with a
// texture (sums != null), bright and blank: the window's gradient sum * 256 < threshold256 * area,
// the window [x - radius, x + radius] clipped, `windowRows` rows high. prefix: width + 1 entries.
void SkyLikeRow(const std::int16_t* HWY_RESTRICT d, const int* HWY_RESTRICT candidateEnd,
                const int* HWY_RESTRICT farLimit, int y, const std::uint8_t* HWY_RESTRICT level,
                const std::int32_t* HWY_RESTRICT sums, int width, int radius, int windowRows, int brightLevel,
                std::int64_t threshold256, std::int64_t* HWY_RESTRICT prefix, std::uint8_t* HWY_RESTRICT out) {
  for (int x = 0; x < width; ++x) {
    const bool far = d[x] != kInvalidDisparity && d[x] < farLimit[x];
    out[x] = static_cast<std::uint8_t>(y < candidateEnd[x] && far ? 1 : 0);
  }
  if (sums == nullptr) return;
  prefix[0] = 0;
  for (int x = 0; x < width; ++x) prefix[x + 1] = prefix[x] + sums[x];
  for (int x = 0; x < width; ++x) {
    const int x0 = std::max(0, x - radius);
    const int x1 = std::min(width - 1, x + radius) + 1;
    const std::int64_t sum = prefix[x1] - prefix[x0];
    const std::int64_t area = static_cast<std::int64_t>(x1 - x0) * windowRows;
    const bool brightBlank = level[x] >= brightLevel && sum * 256 < threshold256 * area;
    out[x] = static_cast<std::uint8_t>(out[x] | (y < candidateEnd[x] && brightBlank ? 1 : 0));
  }
}

// 1 where the row holds a sky pixel within [x - radius, x + radius]. prefix: width + 1 entries.
void NearSkyRow(const std::uint8_t* HWY_RESTRICT sky, int width, int radius, std::int64_t* HWY_RESTRICT prefix,
                std::uint8_t* HWY_RESTRICT out) {
  prefix[0] = 0;
  for (int x = 0; x < width; ++x) prefix[x + 1] = prefix[x] + sky[x];
  for (int x = 0; x < width; ++x) {
    const int x0 = std::max(0, x - radius);
    const int x1 = std::min(width - 1, x + radius) + 1;
    out[x] = static_cast<std::uint8_t>(prefix[x1] - prefix[x0] > 0 ? 1 : 0);
  }
}

// The rim of one row: a bright candidate, not sky, with sky within the radius (`near`: the
// NearSkyRow rows of the window; none without a texture: no rim). Then sky and rim
// pixels lose their disparity; returns how many had one.
std::size_t RimAndRemoveRow(const std::uint8_t* const* near, int nearRows, const std::uint8_t* HWY_RESTRICT sky,
                            const int* HWY_RESTRICT candidateEnd, int y, const std::uint8_t* HWY_RESTRICT level,
                            int brightLevel, int width, std::uint8_t* HWY_RESTRICT nearAny,
                            std::int16_t* HWY_RESTRICT d) {
  std::size_t removed = 0;
  if (nearRows == 0) {
    for (int x = 0; x < width; ++x) {
      const bool drop = sky[x] != 0 && d[x] != kInvalidDisparity;
      removed += drop ? 1 : 0;
      d[x] = drop ? kInvalidDisparity : d[x];
    }
    return removed;
  }
  std::copy(near[0], near[0] + width, nearAny);
  for (int k = 1; k < nearRows; ++k) {
    const std::uint8_t* HWY_RESTRICT row = near[k];
    for (int x = 0; x < width; ++x) nearAny[x] = static_cast<std::uint8_t>(nearAny[x] | row[x]);
  }
  for (int x = 0; x < width; ++x) {
    const bool rim = y < candidateEnd[x] && sky[x] == 0 && level[x] >= brightLevel && nearAny[x] != 0;
    const bool drop = (sky[x] != 0 || rim) && d[x] != kInvalidDisparity;
    removed += drop ? 1 : 0;
    d[x] = drop ? kInvalidDisparity : d[x];
  }
  return removed;
}

}  // namespace HWY_NAMESPACE
}  // namespace fast
}  // namespace lidar_sgm
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace lidar_sgm {
namespace fast {

HWY_EXPORT(LevelsRow8);
HWY_EXPORT(LevelsRow16);
HWY_EXPORT(GradientRow);
HWY_EXPORT(AddRow);
HWY_EXPORT(SkyLikeRow);
HWY_EXPORT(NearSkyRow);
HWY_EXPORT(RimAndRemoveRow);

namespace {

constexpr int kNoSample = std::numeric_limits<int>::max();

template <typename T>
void growTo(std::vector<T>& v, std::size_t n) {
  if (v.size() < n) v.resize(n);
}

// Per column: where the candidates end (the scan's top over +-columnRadius columns, less the
// margin; the whole column without any return nearby) and the far test's limit (the smallest LiDAR
// disparity nearby less the slack; the lowest int, which no disparity is below, without the test).
// Returns the end of the rows that hold any candidate.
int columnLimits(const std::vector<LidarSample>& samples, int width, int height, const SkyFilterOptions& options,
                 FastPassBuffers& b) {
  b.columnTop.assign(static_cast<std::size_t>(width), kNoSample);
  b.columnMin.assign(static_cast<std::size_t>(width), kNoSample);
  for (const LidarSample& s : samples) {
    if (s.x < 0 || s.x >= width || s.y < 0 || s.y >= height) {
      throw std::invalid_argument("removeSky: a LiDAR sample lies outside the disparity image");
    }
    b.columnTop[s.x] = std::min(b.columnTop[s.x], s.y);
    b.columnMin[s.x] = std::min(b.columnMin[s.x], s.disparity16);
  }
  growTo(b.candidateEnd, static_cast<std::size_t>(width));
  growTo(b.farLimit, static_cast<std::size_t>(width));
  const int farSlack16 = static_cast<int>(std::lround(options.farSlack * kDisparityScale));
  int rowsEnd = 0;
  for (int x = 0; x < width; ++x) {
    int top = kNoSample;
    int minDisparity16 = kNoSample;
    const int x1 = std::min(width - 1, x + options.columnRadius);
    for (int xx = std::max(0, x - options.columnRadius); xx <= x1; ++xx) {
      top = std::min(top, b.columnTop[xx]);
      minDisparity16 = std::min(minDisparity16, b.columnMin[xx]);
    }
    b.candidateEnd[x] = top == kNoSample ? height : std::max(0, top - options.marginRows);
    b.farLimit[x] = options.farTest && minDisparity16 != kNoSample ? minDisparity16 - farSlack16
                                                                   : std::numeric_limits<int>::min();
    rowsEnd = std::max(rowsEnd, b.candidateEnd[x]);
  }
  return rowsEnd;
}

// The sky-like pixels 4-connected to the top row, marked 1 in `sky` (rows [0, rows)).
void floodFromTop(const std::uint8_t* skyLike, int width, int rows, std::uint8_t* sky, std::vector<std::size_t>& stack) {
  std::fill(sky, sky + static_cast<std::size_t>(width) * rows, std::uint8_t{0});
  stack.clear();
  for (int x = 0; x < width; ++x) {
    if (skyLike[x] != 0) {
      sky[x] = 1;
      stack.push_back(static_cast<std::size_t>(x));
    }
  }
  const auto visit = [&](std::size_t j) {
    if (skyLike[j] != 0 && sky[j] == 0) {
      sky[j] = 1;
      stack.push_back(j);
    }
  };
  while (!stack.empty()) {
    const std::size_t i = stack.back();
    stack.pop_back();
    const int x = static_cast<int>(i % static_cast<std::size_t>(width));
    const int y = static_cast<int>(i / static_cast<std::size_t>(width));
    if (x > 0) visit(i - 1);
    if (x + 1 < width) visit(i + 1);
    if (y > 0) visit(i - static_cast<std::size_t>(width));
    if (y + 1 < rows) visit(i + static_cast<std::size_t>(width));
  }
}

}  // namespace

std::size_t removeSky(ImageView<std::int16_t> disparity16, const std::vector<LidarSample>& samples,
                      const GrayImageView& left, const SkyFilterOptions& options, FastPassBuffers& b, int threads) {
  validate(options);
  if (!options.enabled || samples.empty()) return 0;
  const int width = disparity16.width;
  const int height = disparity16.height;
  if (!left.empty() && (left.width() != width || left.height() != height)) {
    throw std::invalid_argument("removeSky: the left image and the disparity image differ in size");
  }
  const int rows = columnLimits(samples, width, height, options, b);  // no candidate below
  if (rows == 0) return 0;
  const std::size_t W = static_cast<std::size_t>(width);
  const bool texture = !left.empty();
  const int R = options.textureRadius;
  // The texture windows of the candidate rows reach R rows below them; the gradient one more.
  const int gradientRows = std::min(height, rows + R);
  const int levelRows = std::min(height, gradientRows + 1);
  const int ranges = rangeCount(rows, threads);
  growTo(b.skyLike, W * rows);
  growTo(b.sky, W * rows);
  growTo(b.prefix, (W + 1) * ranges);
  if (texture) {
    growTo(b.levels, W * levelRows);
    growTo(b.gradient, W * gradientRows);
    growTo(b.columnSums, W * ranges);
    growTo(b.nearSkyRow, W * rows);
    growTo(b.nearAny, W * ranges);
    parallelRanges(levelRows, threads, [&](int, int y0, int y1) {
      for (int y = y0; y < y1; ++y) {
        if (!left.gray8.empty()) {
          HWY_DYNAMIC_DISPATCH(LevelsRow8)(left.gray8.row(y), width, b.levels.data() + W * y);
        } else {
          HWY_DYNAMIC_DISPATCH(LevelsRow16)(left.gray16.row(y), width, b.levels.data() + W * y);
        }
      }
    });
    parallelRanges(gradientRows, threads, [&](int, int y0, int y1) {
      for (int y = y0; y < y1; ++y) {
        const std::uint8_t* below = y + 1 < height ? b.levels.data() + W * (y + 1) : nullptr;
        HWY_DYNAMIC_DISPATCH(GradientRow)(b.levels.data() + W * y, below, width, b.gradient.data() + W * y);
      }
    });
  }
  const std::int64_t threshold256 = std::llround(options.textureThreshold * 256.0);
  parallelRanges(rows, threads, [&](int t, int y0, int y1) {
    std::int32_t* sums = texture ? b.columnSums.data() + W * t : nullptr;
    std::int64_t* prefix = b.prefix.data() + (W + 1) * t;
    if (texture) {
      // The window's rows of y0, then slid down one row at a time.
      std::fill(sums, sums + W, 0);
      for (int yy = std::max(0, y0 - R); yy <= std::min(height - 1, y0 + R); ++yy) {
        HWY_DYNAMIC_DISPATCH(AddRow)(b.gradient.data() + W * yy, width, 1, sums);
      }
    }
    for (int y = y0; y < y1; ++y) {
      if (texture && y > y0) {
        if (y + R <= height - 1) HWY_DYNAMIC_DISPATCH(AddRow)(b.gradient.data() + W * (y + R), width, 1, sums);
        if (y - 1 - R >= 0) HWY_DYNAMIC_DISPATCH(AddRow)(b.gradient.data() + W * (y - 1 - R), width, -1, sums);
      }
      const int windowRows = std::min(height - 1, y + R) + 1 - std::max(0, y - R);
      HWY_DYNAMIC_DISPATCH(SkyLikeRow)(disparity16.row(y), b.candidateEnd.data(), b.farLimit.data(), y,
                                       texture ? b.levels.data() + W * y : nullptr, sums, width, R, windowRows,
                                       options.brightLevel, threshold256, prefix, b.skyLike.data() + W * y);
    }
  });
  floodFromTop(b.skyLike.data(), width, rows, b.sky.data(), b.stack);
  if (texture) {
    parallelRanges(rows, threads, [&](int t, int y0, int y1) {
      std::int64_t* prefix = b.prefix.data() + (W + 1) * t;
      for (int y = y0; y < y1; ++y) {
        HWY_DYNAMIC_DISPATCH(NearSkyRow)(b.sky.data() + W * y, width, R, prefix, b.nearSkyRow.data() + W * y);
      }
    });
  }
  b.removedPerRange.assign(static_cast<std::size_t>(ranges), 0);
  parallelRanges(rows, threads, [&](int t, int y0, int y1) {
    const std::uint8_t* near[2 * 32 + 1];
    std::size_t removed = 0;
    for (int y = y0; y < y1; ++y) {
      int nearRows = 0;
      if (texture) {
        // Sky lies only in candidate rows: the window's rows below `rows` hold none.
        for (int yy = std::max(0, y - R); yy <= std::min(rows - 1, y + R); ++yy) near[nearRows++] = b.nearSkyRow.data() + W * yy;
      }
      removed += HWY_DYNAMIC_DISPATCH(RimAndRemoveRow)(near, nearRows, b.sky.data() + W * y, b.candidateEnd.data(), y,
                                                       texture ? b.levels.data() + W * y : nullptr, options.brightLevel,
                                                       width, texture ? b.nearAny.data() + W * t : nullptr,
                                                       disparity16.row(y));
    }
    b.removedPerRange[static_cast<std::size_t>(t)] = removed;
  });
  std::size_t removed = 0;
  for (const std::size_t n : b.removedPerRange) removed += n;
  return removed;
}

}  // namespace fast
}  // namespace lidar_sgm
#endif  // HWY_ONCE
