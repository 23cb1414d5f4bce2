// The confidence's core part (core/confidence_inputs.cpp, the specification) on the fast CPU
// backend: the same integers, from row kernels the compiler vectorises (narrow integer types, no
// bounds checks inside the image), split among the threads by fixed ranges of rows (or, for the
// vertical LiDAR distance, of columns). Each pass reads only what the pass before it wrote
// completely, so no output depends on which thread computed it, nor on how many there were.
// Compiled once per Highway target and chosen at run time, as the other kernels, so that the
// compiler vectorises these loops with the machine's widest vectors (AVX2: 32 bytes) instead of
// the baseline's SSE2.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "backends/cpu/confidence.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include <algorithm>
#include <cstdint>
#include <limits>

#include "backends/cpu/cpu_stages.hpp"
#include "backends/cpu/parallel.hpp"
#include "core/confidence_pixel.hpp"

HWY_BEFORE_NAMESPACE();
namespace lidar_sgm {
namespace cpu {
namespace HWY_NAMESPACE {
namespace {

constexpr auto kCap = static_cast<std::uint8_t>(kLidarDistanceCap);
constexpr std::int16_t kHighest = std::numeric_limits<std::int16_t>::max();
constexpr std::int16_t kLowest = std::numeric_limits<std::int16_t>::min();
static_assert(kInvalidDisparity == kLowest, "the disparity range's max() takes invalid pixels as the lowest value");

template <typename T>
void resizeKeep(std::vector<T>& v, std::size_t n) {
  if (v.size() < n) v.resize(n);
}

template <typename T>
T* rowOf(std::vector<T>& buffer, std::size_t width, int y) {
  return buffer.data() + static_cast<std::size_t>(y) * width;
}

// ---- g: the distance to the nearest LiDAR support ----------------------------------------------

// The vertical distance, top to bottom, of columns [x0, x1): support -> 0, else the row above's + 1.
void verticalFromAbove(const std::uint8_t* __restrict support, const std::uint8_t* __restrict above,
                       std::uint8_t* __restrict v, int x0, int x1) {
  for (int x = x0; x < x1; ++x) {
    const std::uint8_t fromAbove = above == nullptr ? kCap : std::min(static_cast<std::uint8_t>(above[x] + 1), kCap);
    v[x] = support[x] != 0 ? std::uint8_t{0} : fromAbove;
  }
}

// ... then bottom to top: the lower of that and the row below's + 1.
void verticalFromBelow(const std::uint8_t* __restrict below, std::uint8_t* __restrict v, int x0, int x1) {
  for (int x = x0; x < x1; ++x) v[x] = std::min(v[x], std::min(static_cast<std::uint8_t>(below[x] + 1), kCap));
}

// One row of g: min over dx of max(|dx|, v(x + dx)) (Chebyshev), from the row's vertical distances.
// Offsets |dx| >= cap cannot improve on the cap, nor columns outside the image (the core skips them).
void lidarDistanceRow(const std::uint8_t* __restrict v, int width, std::uint8_t* __restrict out) {
  bool far = true;  // no support within `cap` rows: the cap everywhere (the core skips these rows too)
  for (int x = 0; x < width; ++x) far &= v[x] == kCap;
  std::copy(v, v + width, out);
  if (far) return;
  for (int dx = 1; dx < kLidarDistanceCap; ++dx) {
    const auto d = static_cast<std::uint8_t>(dx);
    const int leftEnd = std::min(dx, width);               // [0, leftEnd): no column x - dx
    const int rightBegin = std::max(width - dx, leftEnd);  // [rightBegin, width): no column x + dx
    for (int x = 0; x < leftEnd; ++x) {
      if (x + dx < width) out[x] = std::min(out[x], std::max(d, v[x + dx]));
    }
    for (int x = leftEnd; x < rightBegin; ++x) out[x] = std::min(out[x], std::max(d, std::min(v[x - dx], v[x + dx])));
    for (int x = rightBegin; x < width; ++x) out[x] = std::min(out[x], std::max(d, v[x - dx]));
  }
}

// ---- t and s: texture and saturation ------------------------------------------------------------

// s of one row, and the row's gradient |I(x+1) - I(x-1)| >> shift (border pixels repeated) summed
// over 5 columns (border gradients repeated). `gradient`: width + 4 bytes of scratch.
template <typename T>
void textureRowSums(const T* __restrict in, int width, int shift, T saturation, std::uint8_t* __restrict saturated,
                    std::uint8_t* __restrict gradient, std::uint16_t* __restrict sum) {
  for (int x = 0; x < width; ++x) saturated[x] = static_cast<std::uint8_t>(in[x] >= saturation ? 1 : 0);
  const auto difference = [shift](T a, T b) {  // <= 255 after the shift
    return static_cast<std::uint8_t>(static_cast<T>(a > b ? a - b : b - a) >> shift);
  };
  // The gradient of x at gradient[x + 2]: the window of x is gradient[x .. x + 4].
  gradient[2] = difference(in[std::min(1, width - 1)], in[0]);
  for (int x = 1; x < width - 1; ++x) gradient[x + 2] = difference(in[x + 1], in[x - 1]);
  if (width > 1) gradient[width + 1] = difference(in[width - 1], in[width - 2]);
  gradient[0] = gradient[1] = gradient[2];
  gradient[width + 2] = gradient[width + 3] = gradient[width + 1];
  for (int x = 0; x < width; ++x) {
    sum[x] = static_cast<std::uint16_t>(gradient[x] + gradient[x + 1] + gradient[x + 2] + gradient[x + 3] +
                                        gradient[x + 4]);
  }
}

// t of one row from the 5 rows' column sums around it (clamped at the border): the 5x5 mean,
// rounded, in 16 bits (a window sums to at most 25 * 255).
void textureRow(const std::uint16_t* const* rows, int width, std::uint8_t* __restrict out) {
  const std::uint16_t* __restrict r0 = rows[0];
  const std::uint16_t* __restrict r1 = rows[1];
  const std::uint16_t* __restrict r2 = rows[2];
  const std::uint16_t* __restrict r3 = rows[3];
  const std::uint16_t* __restrict r4 = rows[4];
  for (int x = 0; x < width; ++x) {
    const auto sum = static_cast<std::uint16_t>(r0[x] + r1[x] + r2[x] + r3[x] + r4[x] + 12);
    out[x] = static_cast<std::uint8_t>(std::min<std::uint16_t>(static_cast<std::uint16_t>(sum / 25), 255));
  }
}

template <typename T>
void textureRowSumsOf(const GrayImageView& image, int y, ConfidenceBuffers& b, ImageView<std::uint8_t> saturated);

template <>
void textureRowSumsOf<std::uint8_t>(const GrayImageView& image, int y, ConfidenceBuffers& b,
                                    ImageView<std::uint8_t> saturated) {
  const int W = image.width();
  textureRowSums(image.gray8.row(y), W, 0, std::uint8_t{250}, saturated.row(y), rowOf(b.gradient, W + 4, y),
                 rowOf(b.rowSum, W, y));
}

template <>
void textureRowSumsOf<std::uint16_t>(const GrayImageView& image, int y, ConfidenceBuffers& b,
                                     ImageView<std::uint8_t> saturated) {
  const int W = image.width();
  // 16-bit images in 8-bit units (confidence.hpp).
  textureRowSums(image.gray16.row(y), W, 8, std::uint16_t{250 << 8}, saturated.row(y), rowOf(b.gradient, W + 4, y),
                 rowOf(b.rowSum, W, y));
}

void textureRowSumsAny(const GrayImageView& image, int y, ConfidenceBuffers& b, ImageView<std::uint8_t> saturated) {
  if (!image.gray8.empty()) {
    textureRowSumsOf<std::uint8_t>(image, y, b, saturated);
  } else {
    textureRowSumsOf<std::uint16_t>(image, y, b, saturated);
  }
}

// ---- v: the local disparity range ---------------------------------------------------------------

// The extremes of the valid disparities over 5 columns; a window without any keeps the neutral
// values (kHighest, kLowest), which a valid pixel's own row never has.
void rangeRowExtremes(const std::int16_t* __restrict d, int width, std::int16_t* __restrict lo,
                      std::int16_t* __restrict hi) {
  const auto low = [](std::int16_t value) { return value == kInvalidDisparity ? kHighest : value; };
  const auto border = [&](int x) {
    lo[x] = kHighest;
    hi[x] = kLowest;
    for (int i = std::max(0, x - 2); i <= std::min(width - 1, x + 2); ++i) {
      lo[x] = std::min(lo[x], low(d[i]));
      hi[x] = std::max(hi[x], d[i]);
    }
  };
  const int insideBegin = std::min(2, width);
  const int insideEnd = std::max(insideBegin, width - 2);
  for (int x = 0; x < insideBegin; ++x) border(x);
  for (int x = insideBegin; x < insideEnd; ++x) {
    lo[x] = std::min(std::min(std::min(low(d[x - 2]), low(d[x - 1])), std::min(low(d[x]), low(d[x + 1]))), low(d[x + 2]));
    hi[x] = std::max(std::max(std::max(d[x - 2], d[x - 1]), std::max(d[x], d[x + 1])), d[x + 2]);
  }
  for (int x = insideEnd; x < width; ++x) border(x);
}

// v of one row from the 5 rows' extremes around it (rows clamped at the border repeat a row of
// the window, which changes no minimum or maximum).
void disparityRangeRow(const std::int16_t* const* lows, const std::int16_t* const* highs,
                       const std::int16_t* __restrict d, int width, std::uint8_t* __restrict out) {
  const std::int16_t* __restrict l0 = lows[0];
  const std::int16_t* __restrict l1 = lows[1];
  const std::int16_t* __restrict l2 = lows[2];
  const std::int16_t* __restrict l3 = lows[3];
  const std::int16_t* __restrict l4 = lows[4];
  const std::int16_t* __restrict h0 = highs[0];
  const std::int16_t* __restrict h1 = highs[1];
  const std::int16_t* __restrict h2 = highs[2];
  const std::int16_t* __restrict h3 = highs[3];
  const std::int16_t* __restrict h4 = highs[4];
  for (int x = 0; x < width; ++x) {
    const std::int16_t low = std::min(std::min(std::min(l0[x], l1[x]), std::min(l2[x], l3[x])), l4[x]);
    const std::int16_t high = std::max(std::max(std::max(h0[x], h1[x]), std::max(h2[x], h3[x])), h4[x]);
    // (high - low) / 16 in 16 bits: exact where it is kept (a valid pixel, so high >= low).
    const auto span = static_cast<std::uint16_t>(static_cast<std::uint16_t>(high) - static_cast<std::uint16_t>(low));
    const auto steps = std::min(static_cast<std::int16_t>(span >> kDisparityFractionBits),
                                static_cast<std::int16_t>(kDisparityRangeCap));
    out[x] = static_cast<std::uint8_t>(d[x] == kInvalidDisparity ? 0 : steps);
  }
}

// The 5 row pointers of the window around row y, clamped at the border.
template <typename T>
void windowRows(std::vector<T>& buffer, int width, int height, int y, const T* rows[5]) {
  for (int dy = -2; dy <= 2; ++dy) rows[dy + 2] = rowOf(buffer, width, std::clamp(y + dy, 0, height - 1));
}

// ---- the combination ----------------------------------------------------------------------------

// The core's per-pixel model (confidencePixel, confidenceLogit256, confidenceFromLogit256 in
// core/confidence_pixel.hpp, inline: the one formula) a row at a time: z of a block of pixels from
// the inputs' rows in a loop the compiler vectorises (8- and 16-bit loads, 32-bit products and
// sums), then the sigmoid table's entry per pixel. kPaths > 0: the path count as a constant (c =
// S1 / paths a shift); kLidarOnly: r, t and s read as 0, as confidencePixel reads them.
template <int kPaths, bool kLidarOnly>
void combineRowOf(const ConfidenceInputs& inputs, const ConfidenceModel& model, int paths, const std::int16_t* d,
                  int width, int y, std::uint8_t* out) {
  const int divisor = kPaths > 0 ? kPaths : paths;
  const std::uint8_t* sigmoid = inline_model::sigmoidTable();
  const std::uint8_t* __restrict margin = inputs.margin.view().row(y);
  const std::uint16_t* __restrict bestCost = inputs.bestCost.view().row(y);
  const std::uint8_t* __restrict leftRight = kLidarOnly ? nullptr : inputs.leftRightDifference.view().row(y);
  const std::uint8_t* __restrict lidarDistance = inputs.lidarDistance.view().row(y);
  const std::uint8_t* __restrict texture = kLidarOnly ? nullptr : inputs.texture.view().row(y);
  const std::uint8_t* __restrict saturated = kLidarOnly ? nullptr : inputs.saturated.view().row(y);
  const std::uint8_t* __restrict range = inputs.disparityRange.view().row(y);
  const ConfidenceModel m = model;
  constexpr int kBlock = 256;
  std::int32_t index[kBlock];
  for (int x0 = 0; x0 < width; x0 += kBlock) {
    const int n = std::min(kBlock, width - x0);
    for (int i = 0; i < n; ++i) {
      const int x = x0 + i;
      ConfidencePixel p;
      p.margin = margin[x];
      p.cost = std::min(static_cast<int>(bestCost[x]) / divisor, 255);
      p.leftRight = kLidarOnly ? 0 : leftRight[x];
      p.lidarDistance = lidarDistance[x];
      p.texture = kLidarOnly ? 0 : texture[x];
      p.saturated = kLidarOnly ? 0 : saturated[x];
      p.disparityRange = range[x];
      index[i] = inline_model::tableIndex(inline_model::logit256(m, p));
    }
    for (int i = 0; i < n; ++i) {
      out[x0 + i] = d[x0 + i] == kInvalidDisparity ? std::uint8_t{0} : sigmoid[index[i]];
    }
  }
}

void combineRow(const ConfidenceInputs& inputs, MatchMode mode, const ConfidenceModel& model, int paths,
                const std::int16_t* d, int width, int y, std::uint8_t* out) {
  const bool lidarOnly = mode == MatchMode::LidarOnly;
  if (paths == 4) {
    lidarOnly ? combineRowOf<4, true>(inputs, model, paths, d, width, y, out)
              : combineRowOf<4, false>(inputs, model, paths, d, width, y, out);
  } else if (paths == 8) {
    lidarOnly ? combineRowOf<8, true>(inputs, model, paths, d, width, y, out)
              : combineRowOf<8, false>(inputs, model, paths, d, width, y, out);
  } else {
    lidarOnly ? combineRowOf<0, true>(inputs, model, paths, d, width, y, out)
              : combineRowOf<0, false>(inputs, model, paths, d, width, y, out);
  }
}

void resizeBuffers(ConfidenceBuffers& b, int width, int height, bool texture) {
  const auto pixels = static_cast<std::size_t>(width) * height;
  resizeKeep(b.vertical, pixels);
  if (texture) {
    resizeKeep(b.gradient, static_cast<std::size_t>(width + 4) * height);
    resizeKeep(b.rowSum, pixels);
  }
  resizeKeep(b.rowMin, pixels);
  resizeKeep(b.rowMax, pixels);
}

}  // namespace

void LidarDistanceImpl(ImageView<const std::uint8_t> support, ImageView<std::uint8_t> distance,
                       ConfidenceBuffers& buffers, int threads) {
  const int W = support.width;
  const int H = support.height;
  resizeKeep(buffers.vertical, static_cast<std::size_t>(W) * H);
  std::vector<std::uint8_t>& v = buffers.vertical;
  parallelRanges(W, threads, [&](int x0, int x1) {
    for (int y = 0; y < H; ++y) verticalFromAbove(support.row(y), y == 0 ? nullptr : rowOf(v, W, y - 1), rowOf(v, W, y), x0, x1);
    for (int y = H - 2; y >= 0; --y) verticalFromBelow(rowOf(v, W, y + 1), rowOf(v, W, y), x0, x1);
  });
  parallelRanges(H, threads, [&](int y0, int y1) {
    for (int y = y0; y < y1; ++y) lidarDistanceRow(rowOf(v, W, y), W, distance.row(y));
  });
}

void TextureAndSaturationImpl(const GrayImageView& image, ImageView<std::uint8_t> texture,
                              ImageView<std::uint8_t> saturated, ConfidenceBuffers& buffers, int threads) {
  const int W = texture.width;
  const int H = texture.height;
  if (image.empty()) {
    parallelRanges(H, threads, [&](int y0, int y1) {
      for (int y = y0; y < y1; ++y) {
        std::fill(texture.row(y), texture.row(y) + W, std::uint8_t{0});
        std::fill(saturated.row(y), saturated.row(y) + W, std::uint8_t{0});
      }
    });
    return;
  }
  resizeKeep(buffers.gradient, static_cast<std::size_t>(W + 4) * H);
  resizeKeep(buffers.rowSum, static_cast<std::size_t>(W) * H);
  parallelRanges(H, threads, [&](int y0, int y1) {
    for (int y = y0; y < y1; ++y) textureRowSumsAny(image, y, buffers, saturated);
  });
  parallelRanges(H, threads, [&](int y0, int y1) {
    const std::uint16_t* rows[5];
    for (int y = y0; y < y1; ++y) {
      windowRows(buffers.rowSum, W, H, y, rows);
      textureRow(rows, W, texture.row(y));
    }
  });
}

void DisparityRangeImpl(ImageView<const std::int16_t> disparity, ImageView<std::uint8_t> range,
                        ConfidenceBuffers& buffers, int threads) {
  const int W = disparity.width;
  const int H = disparity.height;
  resizeKeep(buffers.rowMin, static_cast<std::size_t>(W) * H);
  resizeKeep(buffers.rowMax, static_cast<std::size_t>(W) * H);
  parallelRanges(H, threads, [&](int y0, int y1) {
    for (int y = y0; y < y1; ++y) {
      rangeRowExtremes(disparity.row(y), W, rowOf(buffers.rowMin, W, y), rowOf(buffers.rowMax, W, y));
    }
  });
  parallelRanges(H, threads, [&](int y0, int y1) {
    const std::int16_t* lows[5];
    const std::int16_t* highs[5];
    for (int y = y0; y < y1; ++y) {
      windowRows(buffers.rowMin, W, H, y, lows);
      windowRows(buffers.rowMax, W, H, y, highs);
      disparityRangeRow(lows, highs, disparity.row(y), W, range.row(y));
    }
  });
}

void CombineConfidenceImpl(const ConfidenceInputs& inputs, MatchMode mode, int paths,
                           ImageView<const std::int16_t> disparity, ImageView<std::uint8_t> confidence,
                           int threads) {
  const ConfidenceModel& model = confidenceModel(mode);
  parallelRanges(disparity.height, threads, [&](int y0, int y1) {
    for (int y = y0; y < y1; ++y) {
      combineRow(inputs, mode, model, paths, disparity.row(y), disparity.width, y, confidence.row(y));
    }
  });
}

void ConfidenceOfFrameImpl(const GrayImageView& image, ImageView<const std::uint8_t> support,
                           ImageView<const std::int16_t> disparity, MatchMode mode, int paths,
                           ConfidenceInputs& inputs, ImageView<std::uint8_t> confidence, ConfidenceBuffers& buffers,
                           int threads) {
  const int W = disparity.width;
  const int H = disparity.height;
  const bool texture = !image.empty();
  resizeBuffers(buffers, W, H, texture);
  const ConfidenceModel& model = confidenceModel(mode);
  std::vector<std::uint8_t>& v = buffers.vertical;
  // One team, one barrier: what needs neighbouring rows (or, for the vertical distance, whole
  // columns) first, then every input and the confidence row by row, while the row is in cache.
#pragma omp parallel num_threads(std::max(1, std::min(threads, std::min(W, H))))
  {
    const int team = teamSize();
    const int t = threadIndex();
    const int x0 = partBegin(W, team, t);
    const int x1 = partBegin(W, team, t + 1);
    for (int y = 0; y < H; ++y) verticalFromAbove(support.row(y), y == 0 ? nullptr : rowOf(v, W, y - 1), rowOf(v, W, y), x0, x1);
    for (int y = H - 2; y >= 0; --y) verticalFromBelow(rowOf(v, W, y + 1), rowOf(v, W, y), x0, x1);
    const int y0 = partBegin(H, team, t);
    const int y1 = partBegin(H, team, t + 1);
    for (int y = y0; y < y1; ++y) {
      if (texture) textureRowSumsAny(image, y, buffers, inputs.saturated.view());
      rangeRowExtremes(disparity.row(y), W, rowOf(buffers.rowMin, W, y), rowOf(buffers.rowMax, W, y));
    }
#pragma omp barrier
    const std::uint16_t* sums[5];
    const std::int16_t* lows[5];
    const std::int16_t* highs[5];
    for (int y = y0; y < y1; ++y) {
      lidarDistanceRow(rowOf(v, W, y), W, inputs.lidarDistance.view().row(y));
      if (texture) {
        windowRows(buffers.rowSum, W, H, y, sums);
        textureRow(sums, W, inputs.texture.view().row(y));
      } else {
        std::fill(inputs.texture.view().row(y), inputs.texture.view().row(y) + W, std::uint8_t{0});
        std::fill(inputs.saturated.view().row(y), inputs.saturated.view().row(y) + W, std::uint8_t{0});
      }
      windowRows(buffers.rowMin, W, H, y, lows);
      windowRows(buffers.rowMax, W, H, y, highs);
      disparityRangeRow(lows, highs, disparity.row(y), W, inputs.disparityRange.view().row(y));
      combineRow(inputs, mode, model, paths, disparity.row(y), W, y, confidence.row(y));
    }
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace cpu
}  // namespace lidar_sgm
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace lidar_sgm {
namespace cpu {

HWY_EXPORT(LidarDistanceImpl);
HWY_EXPORT(TextureAndSaturationImpl);
HWY_EXPORT(DisparityRangeImpl);
HWY_EXPORT(CombineConfidenceImpl);
HWY_EXPORT(ConfidenceOfFrameImpl);

void lidarDistance(ImageView<const std::uint8_t> support, ImageView<std::uint8_t> distance,
                   ConfidenceBuffers& buffers, int threads) {
  HWY_DYNAMIC_DISPATCH(LidarDistanceImpl)(support, distance, buffers, threads);
}

void textureAndSaturation(const GrayImageView& image, ImageView<std::uint8_t> texture,
                          ImageView<std::uint8_t> saturated, ConfidenceBuffers& buffers, int threads) {
  HWY_DYNAMIC_DISPATCH(TextureAndSaturationImpl)(image, texture, saturated, buffers, threads);
}

void disparityRange(ImageView<const std::int16_t> disparity, ImageView<std::uint8_t> range,
                    ConfidenceBuffers& buffers, int threads) {
  HWY_DYNAMIC_DISPATCH(DisparityRangeImpl)(disparity, range, buffers, threads);
}

void combineConfidence(const ConfidenceInputs& inputs, MatchMode mode, int paths,
                       ImageView<const std::int16_t> disparity, ImageView<std::uint8_t> confidence, int threads) {
  HWY_DYNAMIC_DISPATCH(CombineConfidenceImpl)(inputs, mode, paths, disparity, confidence, threads);
}

void confidenceOfFrame(const GrayImageView& image, ImageView<const std::uint8_t> support,
                       ImageView<const std::int16_t> disparity, MatchMode mode, int paths, ConfidenceInputs& inputs,
                       ImageView<std::uint8_t> confidence, ConfidenceBuffers& buffers, int threads) {
  HWY_DYNAMIC_DISPATCH(ConfidenceOfFrameImpl)(image, support, disparity, mode, paths, inputs, confidence, buffers,
                                              threads);
}

}  // namespace cpu
}  // namespace lidar_sgm
#endif  // HWY_ONCE
