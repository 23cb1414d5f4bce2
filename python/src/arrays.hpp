#pragma once
// numpy arrays in and out: LiDAR points, images (as views where the layout allows), and the
// Densifier's outputs as new arrays (the Densifier reuses its buffers on the next frame).

#include <cstdint>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include "lidar_sgm/core/image.hpp"
#include "lidar_sgm/geometry/reprojection.hpp"

namespace lidar_sgm {
namespace python {

namespace py = pybind11;

/// An (N, 3) or (N, 4) float32 / float64 array (x, y, z [, intensity], any strides) into
/// `points` (x, y, z as float, as PCL and the .bin files hold them). ValueError otherwise.
void pointsFromArray(const py::handle& array, std::vector<Eigen::Vector3f>& points);

/// A camera image: (H, W) gray or (H, W, 3) RGB, uint8 or uint16, wrapped without a copy when
/// its rows are contiguous pixels (any row stride); otherwise copied once into a C-contiguous
/// array, which `owner` keeps alive.
struct ImageArray {
  cv::Mat mat;      ///< RGB order for 3 channels; points into the array's memory
  py::object owner; ///< the array `mat` points into
};
/// ValueError naming `name`, the expected layouts and what was given.
ImageArray imageFromArray(const py::handle& array, const char* name);

/// What the tool matches: the gray levels at full depth (cv::cvtColor's BT.601 weights, as
/// lidar_sgm::io::toGray; gray images are returned as they are, not copied).
cv::Mat grayOf(const cv::Mat& image);
/// What the tool colors the output with (lidar_sgm::io::toColor, in RGB order): 16 bit scaled
/// by 1/257, gray expanded. An 8-bit RGB image is returned as it is, not copied.
cv::Mat colorOf(const cv::Mat& image);
/// A view of an 8-bit, 3-channel cv::Mat as Rgb8 pixels (no copy).
ImageView<const Rgb8> rgbView(const cv::Mat& rgb);

/// x16 disparities (kInvalidDisparity) -> (H, W) float32 [px], NaN where there is none.
py::array_t<float> disparityArray(const Image<std::int16_t>& disparity16);
/// A copy of an image as an (H, W) array of its type.
template <typename T>
py::array_t<T> imageArray(const Image<T>& image);
/// The cloud's points as an (M, 3) float32 array, and their pixels as an (M, 2) int32 (x, y).
py::array_t<float> pointsArray(const geometry::DenseCloud& cloud);
py::array_t<std::int32_t> pixelsArray(const geometry::DenseCloud& cloud);

/// "shape (2, 3) float64": what was given, for messages.
std::string describeArray(const py::handle& array);

}  // namespace python
}  // namespace lidar_sgm
