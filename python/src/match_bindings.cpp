// match: the stereo / LiDAR matcher alone on images and a sparse disparity, as lidar_sgm_disparity.
#include <cmath>
#include <stdexcept>
#include <string>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include "arrays.hpp"
#include "bindings.hpp"
#include "frame_images.hpp"
#include "lidar_sgm/core/lidar_points.hpp"
#include "lidar_sgm/pipeline/densifier.hpp"
#include "options.hpp"

namespace lidar_sgm {
namespace python {

namespace py = pybind11;

namespace {

/// (H, W) float disparities [px], NaN or <= 0 = no point -> x16 fixed point, rounded as
/// io::readKittiDisparity rounds a KITTI PNG's d*256 (so d = v/256 gives the tool's value).
template <typename T>
Image<std::int16_t> sparseDisparity(const py::array& array) {
  const auto a = array.unchecked<T, 2>();
  Image<std::int16_t> sparse(static_cast<int>(a.shape(1)), static_cast<int>(a.shape(0)), kInvalidDisparity);
  for (py::ssize_t y = 0; y < a.shape(0); ++y) {
    for (py::ssize_t x = 0; x < a.shape(1); ++x) {
      const double d = static_cast<double>(a(y, x));
      if (!(d > 0.0)) continue;  // NaN too
      const double d16 = std::floor(d * kDisparityScale + 0.5);
      if (!(d16 <= 32767.0)) {
        throw std::invalid_argument("lidar_disparity: " + std::to_string(d) + " px at (" + std::to_string(x) + ", " +
                                    std::to_string(y) + ") is beyond the x16 range (at most 2047.9375 px)");
      }
      sparse(static_cast<int>(x), static_cast<int>(y)) = static_cast<std::int16_t>(d16);
    }
  }
  return sparse;
}

LidarPoints lidarFromArray(const py::handle& array) {
  const bool f32 = py::isinstance<py::array_t<float>>(array);
  const bool f64 = py::isinstance<py::array_t<double>>(array);
  const py::array a = (f32 || f64) ? py::reinterpret_borrow<py::array>(array) : py::array();
  if (!(f32 || f64) || a.ndim() != 2) {
    throw std::invalid_argument("lidar_disparity: expected an (H, W) array of float32 or float64 (disparity [px], NaN "
                                "or 0 = no point), got " + describeArray(array));
  }
  const Image<std::int16_t> sparse = f32 ? sparseDisparity<float>(a) : sparseDisparity<double>(a);
  return LidarPoints::fromDisparityImage(sparse.view());
}

py::array_t<float> match(const py::object& left, const py::object& right, const py::object& lidarDisparity,
                         const py::kwargs& parameters) {
  Densifier densifier;
  configure(densifier, parameters, OptionSet::Match);
  const FrameImages images = frameImages(left, right);
  LidarPoints lidar;
  if (!lidarDisparity.is_none()) lidar = lidarFromArray(lidarDisparity);
  if (images.right.mat.empty() && lidar.empty()) {
    throw std::invalid_argument("nothing to match: give left and right, lidar_disparity (with at least one point), "
                                "or all three");
  }
  if (!images.left.mat.empty() && !lidar.empty() &&
      (lidar.width() != images.left.mat.cols || lidar.height() != images.left.mat.rows)) {
    throw std::invalid_argument("lidar_disparity is " + std::to_string(lidar.width()) + "x" +
                                std::to_string(lidar.height()) + " but the images are " +
                                std::to_string(images.left.mat.cols) + "x" + std::to_string(images.left.mat.rows));
  }
  {
    py::gil_scoped_release release;
    setImages(densifier, images, false);
    densifier.runProjected(lidar.empty() ? nullptr : &lidar);
  }
  return disparityArray(densifier.disparity());
}

}  // namespace

void bindMatch(py::module_& m) {
  static const std::string doc =
      "match(left, right=None, lidar_disparity=None, **parameters) -> (H, W) float32 disparity [px], NaN = none\n\n"
      "The matcher alone, as lidar_sgm_disparity: left + right -> stereo-only census SGM; + lidar_disparity ->\n"
      "fused (Eq. 5); lidar_disparity alone (left None or given) -> LiDAR-only SGM. left / right: (H, W) gray or\n"
      "(H, W, 3) RGB, uint8 or uint16; lidar_disparity: (H, W) float32/float64 sparse disparities of the left\n"
      "image [px] (NaN or <= 0 = no point; a KITTI PNG's values / 256). The GIL is released while matching.\n"
      "ValueError for bad arrays or parameters.\n\n" +
      parametersHelp(OptionSet::Match);
  m.def("match", &match, py::arg("left"), py::arg("right") = py::none(), py::arg("lidar_disparity") = py::none(),
        doc.c_str());
}

}  // namespace python
}  // namespace lidar_sgm
