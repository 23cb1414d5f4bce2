// geometry::depthImage and geometry::reproject (reprojection.cpp, the specification), fast: rows
// split among threads; the cloud's points are counted per row first, so that every row writes
// its points at their place in the specification's row-major order; z of each disparity from a
// table (depth_table.hpp), the same quotient without a division per pixel. No SIMD: the arithmetic
// is double precision, and a vectorised (or fused multiply-add) version would round differently;
// the expressions are the specification's, compiled with the same flags.
#include <limits>

#include "geometry/reprojection_checks.hpp"
#include "pipeline/fast/fast_passes.hpp"
#include "pipeline/fast/parallel.hpp"

namespace lidar_sgm {
namespace fast {

void depthImage(ImageView<const std::int16_t> disparity16, double focalBaseline, double maxDepth, Image<float>& depth,
                FastPassBuffers& buffers, int threads) {
  geometry::checkDepthImageInputs(focalBaseline, maxDepth);
  depth.resize(disparity16.width, disparity16.height);
  DepthTable& table = buffers.depthTable;
  table.prepare(focalBaseline);
  const ImageView<float> out = depth.view();
  parallelRanges(disparity16.height, threads, [&](int, int y0, int y1) {
    for (int y = y0; y < y1; ++y) {
      const std::int16_t* in = disparity16.row(y);
      float* row = out.row(y);
      for (int x = 0; x < disparity16.width; ++x) {
        const int d16 = in[x];
        const double z = d16 > 0 ? table.depth(d16) : 0.0;
        row[x] = z > 0.0 && z <= maxDepth ? static_cast<float>(z) : 0.0f;
      }
    }
  });
}

void reproject(ImageView<const std::int16_t> disparity16, const geometry::StereoCalibration& calibration,
               const geometry::ReprojectionOptions& options, geometry::DenseCloud& cloud, FastPassBuffers& buffers,
               int threads) {
  geometry::checkReprojectionInputs(disparity16.width, disparity16.height, calibration, options);

  const Eigen::Isometry3d T_out_cam = options.frame == geometry::OutputFrame::Lidar ? calibration.T_lidar_cam()
                                                                                     : Eigen::Isometry3d::Identity();
  DepthTable& table = buffers.depthTable;
  table.prepare(calibration.focalBaseline());
  // The specification's test, !(d16 invalid or <= 0 or z > maxDepth), as one comparison: z falls
  // as d16 grows, and kInvalidDisparity is negative.
  const int firstPoint = table.firstWithin(options.maxDepth);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const int stride = options.stride;
  const int columns = (calibration.width + stride - 1) / stride;
  const int rows = (calibration.height + stride - 1) / stride;

  // Each sampled row's first point: every sampled pixel when organized, else the valid ones.
  std::vector<int>& first = buffers.rowPoints;
  first.assign(static_cast<std::size_t>(rows) + 1, 0);
  if (options.keepOrganized) {
    for (int r = 0; r <= rows; ++r) first[static_cast<std::size_t>(r)] = r * columns;
  } else {
    parallelRanges(rows, threads, [&](int, int r0, int r1) {
      for (int r = r0; r < r1; ++r) {
        const std::int16_t* in = disparity16.row(r * stride);
        int n = 0;
        for (int x = 0; x < calibration.width; x += stride) n += in[x] >= firstPoint ? 1 : 0;
        first[static_cast<std::size_t>(r) + 1] = n;
      }
    });
    for (int r = 0; r < rows; ++r) first[static_cast<std::size_t>(r) + 1] += first[static_cast<std::size_t>(r)];
  }
  const auto total = static_cast<std::size_t>(first[static_cast<std::size_t>(rows)]);
  cloud.points.resize(total);
  cloud.pixels.resize(total);
  const int ranges = rangeCount(rows, threads);
  buffers.removedPerRange.assign(static_cast<std::size_t>(ranges), 0);  // here: NaN points per range
  parallelRanges(rows, threads, [&](int t, int r0, int r1) {
    std::size_t missing = 0;
    for (int r = r0; r < r1; ++r) {
      const int y = r * stride;
      const std::int16_t* in = disparity16.row(y);
      auto i = static_cast<std::size_t>(first[static_cast<std::size_t>(r)]);
      for (int x = 0; x < calibration.width; x += stride) {
        const int d16 = in[x];
        if (d16 < firstPoint) {
          if (options.keepOrganized) {
            cloud.points[i] = Eigen::Vector3f(nan, nan, nan);
            cloud.pixels[i] = {x, y};
            ++i;
            ++missing;
          }
          continue;
        }
        const double z = table.depth(d16);
        const Eigen::Vector3d camera((x - calibration.cx()) * z / calibration.fx(),
                                     (y - calibration.cy()) * z / calibration.fy(), z);
        cloud.points[i] = (T_out_cam * camera).cast<float>();
        cloud.pixels[i] = {x, y};
        ++i;
      }
    }
    buffers.removedPerRange[static_cast<std::size_t>(t)] = missing;
  });
  cloud.isDense = true;
  for (const std::size_t n : buffers.removedPerRange) cloud.isDense = cloud.isDense && n == 0;
  if (options.keepOrganized) {
    cloud.width = columns;
    cloud.height = rows;
  } else {
    cloud.width = static_cast<int>(total);
    cloud.height = 1;
  }
}

}  // namespace fast
}  // namespace lidar_sgm
