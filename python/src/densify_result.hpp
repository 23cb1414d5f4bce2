#pragma once
// DensifyResult: one Densifier.densify call's outputs as Python objects (numpy arrays), shared by
// the Densifier binding that makes it and write_cloud, which writes it as the tool writes its cloud.

#include <string>

#include <pybind11/pybind11.h>

namespace lidar_sgm {
namespace python {

/// One frame's outputs: the cloud moved out of the Densifier, the images copied (it reuses their
/// buffers).
struct DensifyResult {
  pybind11::object points;      ///< (M, 3) float32, the output frame (LiDAR by default)
  pybind11::object colors;      ///< (M, 3) uint8 RGB, None without a left image
  pybind11::object pixels;      ///< (M, 2) int32: the (x, y) pixel each point came from
  /// (M,) float32 in [0, 1]: each point's confidence (its pixel's / 255), the tool's `confidence`
  /// field; None with no_confidence
  pybind11::object pointConfidence;
  pybind11::object disparity;   ///< (H, W) float32 [px], NaN where none
  pybind11::object depth;       ///< (H, W) float32 [m], 0 where none or beyond max_depth
  pybind11::object confidence;  ///< (H, W) uint8, 255 x P(correct), 0 where none; None with no_confidence
  pybind11::dict timings;       ///< project, match, reproject, total [ms]
  pybind11::dict projection;    ///< what happened to the input points
  std::string mode;             ///< "fused", "lidar-only", "stereo-only"
  std::string backend;          ///< the backend that matched
  std::string frame;            ///< "lidar" or "camera"
  pybind11::tuple disparityRange;  ///< (min_disparity, num_disparities) matched
  int width = 0;                ///< organized (keep_organized): sampled columns; else the point count
  int height = 0;               ///< organized: sampled rows; else 1
  bool isDense = true;          ///< no NaN point (the cloud's is_dense, as the tool writes it)
};

}  // namespace python
}  // namespace lidar_sgm
