#include "core/half_scale.hpp"

#include <algorithm>
#include <utility>
#include <vector>

#ifdef _OPENMP  // the core has OpenMP when the cpu backend brings it (not on a GPU machine's bare build)
#include "core/parallel_ranges.hpp"
#endif

namespace lidar_sgm {
namespace {

// body(begin, end) on fixed ranges of [0, count) in parallel (parallel_ranges.hpp), or on the
// whole of it without OpenMP. Every row below is computed alone, so no result depends on the split.
template <typename Body>
void forRowRanges(int count, int threads, const Body& body) {
#ifdef _OPENMP
  parallelParts(count, threads, [&](int, int begin, int end) { body(begin, end); });
#else
  (void)threads;
  body(0, count);
#endif
}

template <typename Pixel>
void downscaleHalfImpl(ImageView<const Pixel> in, Image<Pixel>& out, int threads) {
  out.resize(halfSize(in.width), halfSize(in.height));
  const ImageView<Pixel> view = out.view();
  forRowRanges(view.height, threads, [&](int y0, int y1) {
    for (int y = y0; y < y1; ++y) {
      const Pixel* row0 = in.row(2 * y);
      const Pixel* row1 = in.row(std::min(2 * y + 1, in.height - 1));
      Pixel* dst = view.row(y);
      for (int x = 0; x < view.width; ++x) {
        const int x0 = 2 * x;
        const int x1 = std::min(x0 + 1, in.width - 1);
        const std::uint32_t sum = std::uint32_t{row0[x0]} + row0[x1] + row1[x0] + row1[x1];
        dst[x] = static_cast<Pixel>((sum + 2) >> 2);
      }
    }
  });
}

// Rows 2k and 2k + 1 of `full` from row k of `half` (value(v) for each), for the half rows split
// among the threads: each half row is widened once and copied once.
template <typename T, typename Value>
void upscaleRows(ImageView<const T> half, ImageView<T> full, int threads, const Value& value) {
  const int halfRows = std::min(half.height, (full.height + 1) / 2);
  forRowRanges(halfRows, threads, [&](int k0, int k1) {
    for (int k = k0; k < k1; ++k) {
      T* dst = full.row(2 * k);
      const T* src = half.row(k);
      for (int x = 0; x < full.width; ++x) dst[x] = value(src[x / 2]);
      if (2 * k + 1 < full.height) std::copy(dst, dst + full.width, full.row(2 * k + 1));
    }
  });
}

}  // namespace

void downscaleHalf(ImageView<const std::uint8_t> in, Image<std::uint8_t>& out, int threads) {
  downscaleHalfImpl(in, out, threads);
}
void downscaleHalf(ImageView<const std::uint16_t> in, Image<std::uint16_t>& out, int threads) {
  downscaleHalfImpl(in, out, threads);
}

GrayImageView downscaleHalf(const GrayImageView& in, Image<std::uint8_t>& buffer8, Image<std::uint16_t>& buffer16,
                            int threads) {
  if (in.empty()) return {};
  if (!in.gray8.empty()) {
    downscaleHalf(in.gray8, buffer8, threads);
    return GrayImageView(std::as_const(buffer8).view());
  }
  downscaleHalf(in.gray16, buffer16, threads);
  return GrayImageView(std::as_const(buffer16).view());
}

void halveLidarPoints(const LidarPoints& points, std::vector<LidarSample>& samples, LidarPoints& half) {
  // The points in their stored order (ascending pixel, then as given): the order of a walk over
  // the pixels, without reading the offsets of the many pixels that hold none.
  const std::vector<int>& pixels = points.pointPixels();
  const std::vector<int>& disparities = points.disparities16();
  const int width = points.width();
  samples.resize(pixels.size());
  for (std::size_t i = 0; i < pixels.size(); ++i) {
    const int x = pixels[i] % width;
    const int y = pixels[i] / width;
    samples[i] = {x / 2, y / 2, (disparities[i] + 1) / 2};
  }
  half.assign(halfSize(points.width()), halfSize(points.height()), samples);
}

LidarPoints halveLidarPoints(const LidarPoints& points) {
  std::vector<LidarSample> samples;
  LidarPoints half;
  halveLidarPoints(points, samples, half);
  return half;
}

void upscaleDisparity(ImageView<const std::int16_t> half, ImageView<std::int16_t> full, int threads) {
  upscaleRows(half, full, threads, [](std::int16_t d) {
    return d == kInvalidDisparity ? kInvalidDisparity : static_cast<std::int16_t>(2 * d);
  });
}

void upscaleMask(ImageView<const std::uint8_t> half, ImageView<std::uint8_t> full, int threads) {
  upscaleRows(half, full, threads, [](std::uint8_t v) { return v; });
}

}  // namespace lidar_sgm
