// Calibration (geometry::StereoCalibration) from arrays or from the files the tools read.
#include <cmath>
#include <stdexcept>
#include <string>

#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include "arrays.hpp"
#include "bindings.hpp"
#include "errors.hpp"
#include "lidar_sgm/geometry/calibration.hpp"
#include "lidar_sgm/io/calibration_io.hpp"

namespace lidar_sgm {
namespace python {

namespace py = pybind11;
using geometry::StereoCalibration;

namespace {

/// Validates all but the size when it is still unknown (0 x 0: KITTI object files carry none; the
/// images give it), so that a bad K, baseline or rotation is reported where it is made.
void validateKnown(const StereoCalibration& c) {
  StereoCalibration check = c;
  if (check.width == 0 && check.height == 0) {
    check.width = 1;
    check.height = 1;
  }
  check.validate();
}

/// A rows x cols matrix of numbers from any array-like, or ValueError naming `name`, the shape
/// wanted and what was given (pybind's own cast says only "Unable to cast Python instance").
template <int Rows, int Cols>
Eigen::Matrix<double, Rows, Cols> matrixFrom(const py::object& value, const char* name) {
  // ensure() converts lists and other dtypes, and returns an empty handle when it cannot.
  const auto array = py::array_t<double, py::array::forcecast>::ensure(value);
  if (!array || array.ndim() != 2 || array.shape(0) != Rows || array.shape(1) != Cols) {
    throw std::invalid_argument(std::string(name) + ": expected a " + std::to_string(Rows) + "x" +
                                std::to_string(Cols) + " matrix of numbers, got " +
                                (array ? describeArray(array) : describeArray(value)));
  }
  Eigen::Matrix<double, Rows, Cols> m;
  const auto cells = array.unchecked<2>();
  for (int r = 0; r < Rows; ++r) {
    for (int c = 0; c < Cols; ++c) m(r, c) = cells(r, c);
  }
  return m;
}

StereoCalibration makeCalibration(const py::object& K, double baseline, const py::object& T, int width,
                                  int height) {
  StereoCalibration c;
  c.K = matrixFrom<3, 3>(K, "K");
  c.baseline = baseline;
  c.width = width;
  c.height = height;
  if (!T.is_none()) {
    const Eigen::Matrix4d m = matrixFrom<4, 4>(T, "T_cam_lidar");
    if (!(m.row(3) - Eigen::RowVector4d(0, 0, 0, 1)).isZero(0.0)) {
      throw std::invalid_argument("T_cam_lidar: the last row of the 4x4 transform must be (0 0 0 1)");
    }
    c.T_cam_lidar.matrix() = m;
  }
  validateKnown(c);
  return c;
}

}  // namespace

void bindCalibration(py::module_& m) {
  py::class_<StereoCalibration>(m, "Calibration",
                                "A rectified stereo rig with its LiDAR (metres, pixels): K, baseline, T_cam_lidar\n"
                                "(p_cam = T_cam_lidar @ p_lidar) and the rectified image size; d = f*b/z (Eq. 3).")
      .def(py::init(&makeCalibration), py::arg("K"), py::arg("baseline"), py::arg("T_cam_lidar") = py::none(),
           py::arg("width") = 0, py::arg("height") = 0,
           "Calibration(K, baseline, T_cam_lidar=None, width=0, height=0)\n\n"
           "K: 3x3 rectified left intrinsics (no skew); baseline [m] > 0; T_cam_lidar: 4x4 LiDAR -> left\n"
           "camera (None: identity); width, height: the rectified image size (0, 0: taken from the images).\n"
           "ValueError naming the first problem (as StereoCalibration::validate).")
      .def_property_readonly("K", [](const StereoCalibration& c) { return Eigen::Matrix3d(c.K); },
                             "3x3 rectified left intrinsics (a copy)")
      .def_readonly("baseline", &StereoCalibration::baseline, "distance between the rectified cameras [m]")
      .def_property_readonly("T_cam_lidar", [](const StereoCalibration& c) { return Eigen::Matrix4d(c.T_cam_lidar.matrix()); },
                             "4x4 transform LiDAR -> rectified left camera (a copy)")
      .def_readonly("width", &StereoCalibration::width, "rectified image width [px] (0: unknown)")
      .def_readonly("height", &StereoCalibration::height, "rectified image height [px] (0: unknown)")
      .def_property_readonly("focal_baseline", &StereoCalibration::focalBaseline, "f*b [px*m]: d = f*b / z")
      .def("validate", &StereoCalibration::validate, "Raises ValueError naming the first problem (size included).")
      .def("__repr__", [](const StereoCalibration& c) { return "<lidar_sgm.Calibration " + geometry::describe(c) + ">"; });

  m.def(
      "read_calibration",
      [](const std::string& path, int width, int height) {
        return readingFile([&] { return io::readCalibration(path, width, height); });
      },
      py::arg("path"), py::arg("width") = 0, py::arg("height") = 0,
      "read_calibration(path, width=0, height=0) -> Calibration\n\n"
      "As the tools' -calib: *.yaml / *.yml -> our YAML; a folder, or calib_cam_to_cam.txt -> KITTI raw\n"
      "(calib_velo_to_cam.txt beside it); any other file -> KITTI object (P2, P3, R0_rect, Tr_velo_to_cam),\n"
      "which has no image size: give it, or leave 0 and the images give it. OSError for a missing,\n"
      "unreadable or malformed file (the message names the file, line and key).");
}

}  // namespace python
}  // namespace lidar_sgm
