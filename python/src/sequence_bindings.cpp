// Whole sequences for mapping users (lidar_sgm::sequence): a drive's frames in the KITTI layouts
// or a list file, each frame's calibration, the drive's poses, and the voxel map the batch tool
// merges its clouds into.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <Eigen/Geometry>
#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "arrays.hpp"
#include "bindings.hpp"
#include "errors.hpp"
#include "lidar_sgm/sequence/frame_calibration.hpp"
#include "lidar_sgm/sequence/frame_list.hpp"
#include "lidar_sgm/sequence/poses.hpp"
#include "lidar_sgm/sequence/voxel_map.hpp"

namespace lidar_sgm {
namespace python {

namespace py = pybind11;
using sequence::Frame;
using sequence::VoxelMap;

namespace {

/// `map`'s points, one per voxel: (N, 3) float32 positions, (N, 3) uint8 colors (RGB), (N,)
/// float32 confidences.
py::tuple mapArrays(const VoxelMap& map) {
  const pcl::PointCloud<PointXYZRGBConfidence> points = map.points();
  const std::size_t n = points.size();
  auto xyz = newArray<float>(n, 3);
  auto rgb = newArray<std::uint8_t>(n, 3);
  py::array_t<float> confidence = newArrayOfShape<float>({static_cast<py::ssize_t>(n)});
  float* p = xyz.mutable_data();
  std::uint8_t* c = rgb.mutable_data();
  float* q = confidence.mutable_data();
  for (std::size_t i = 0; i < n; ++i) {
    const PointXYZRGBConfidence& point = points[i];
    p[3 * i] = point.x;
    p[3 * i + 1] = point.y;
    p[3 * i + 2] = point.z;
    c[3 * i] = point.r;
    c[3 * i + 1] = point.g;
    c[3 * i + 2] = point.b;
    q[i] = point.confidence;
  }
  return py::make_tuple(xyz, rgb, confidence);
}

void addToMap(VoxelMap& map, const py::handle& pointsArray, const py::object& colors, const py::object& confidence,
              const Eigen::Matrix4d& toWorld) {
  std::vector<Eigen::Vector3f> points;
  pointsFromArray(pointsArray, points);
  sequence::MapInput input;
  input.points.resize(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    input.points[i].x = points[i].x();
    input.points[i].y = points[i].y();
    input.points[i].z = points[i].z();
  }
  if (!colors.is_none()) {
    const auto rgb = py::array_t<std::uint8_t, py::array::forcecast>::ensure(colors);
    if (!rgb || rgb.ndim() != 2 || rgb.shape(1) != 3 || static_cast<std::size_t>(rgb.shape(0)) != points.size()) {
      throw std::invalid_argument("colors: expected an (N, 3) array of 0..255 values for the N points, got " +
                                  describeArray(colors));
    }
    const auto c = rgb.unchecked<2>();
    for (std::size_t i = 0; i < points.size(); ++i) {
      const auto row = static_cast<py::ssize_t>(i);
      input.points[i].r = c(row, 0);
      input.points[i].g = c(row, 1);
      input.points[i].b = c(row, 2);
    }
    input.hasColor = true;
  }
  if (!confidence.is_none()) {
    const auto values = py::array_t<float, py::array::forcecast>::ensure(confidence);
    if (!values || values.ndim() != 1 || static_cast<std::size_t>(values.shape(0)) != points.size()) {
      throw std::invalid_argument("confidence: expected an (N,) array for the N points, got " +
                                  describeArray(confidence));
    }
    const auto v = values.unchecked<1>();
    for (std::size_t i = 0; i < points.size(); ++i) input.points[i].confidence = v(static_cast<py::ssize_t>(i));
    input.hasConfidence = true;
  }
  if (!(toWorld.row(3) - Eigen::RowVector4d(0, 0, 0, 1)).isZero(0.0)) {
    throw std::invalid_argument("to_world: the last row of the 4x4 transform must be (0 0 0 1)");
  }
  Eigen::Isometry3d transform;
  transform.matrix() = toWorld;
  py::gil_scoped_release release;
  map.add(input, transform);
}

}  // namespace

void bindSequence(py::module_& m) {
  py::class_<Frame>(m, "Frame",
                    "One frame of a sequence: its name (unique, the output's stem) and its files; left and\n"
                    "right are '' when absent, oxts is a KITTI raw drive's OXTS packet ('' otherwise),\n"
                    "velo_to_cam the calib_velo_to_cam file of KITTI stereo 2015's per-frame calibration\n"
                    "('' otherwise).")
      .def_readonly("name", &Frame::name)
      .def_readonly("scan", &Frame::scan)
      .def_readonly("left", &Frame::left)
      .def_readonly("right", &Frame::right)
      .def_readonly("calib", &Frame::calib)
      .def_readonly("velo_to_cam", &Frame::veloToCam)
      .def_readonly("oxts", &Frame::oxts)
      .def("__repr__", [](const Frame& f) { return "<lidar_sgm.Frame " + f.name + ": " + f.scan + ">"; });

  m.def(
      "frames",
      [](const std::string& path) {
        std::error_code ec;
        return std::filesystem::is_directory(path, ec) ? sequence::framesFromDirectory(path)
                                                       : sequence::framesFromList(path);
      },
      py::arg("path"),
      "frames(path) -> list[Frame]: the frames of a KITTI odometry sequence (or the dataset's\n"
      "sequences/ root), a KITTI raw drive, a KITTI object layout, KITTI stereo 2015 training with\n"
      "its raw scans (velodyne/NNNNNN_10.bin), or a list file (SCAN LEFT RIGHT CALIB per line), in\n"
      "name order, as lidar_sgm_batch -input_dir / -list reads them. ValueError naming the path and\n"
      "the layouts looked for otherwise.");
  m.def(
      "read_frame_calibration",
      [](const Frame& frame, int width, int height) {
        return readingFile([&] { return sequence::readFrameCalibration(frame, width, height); });
      },
      py::arg("frame"), py::arg("width") = 0, py::arg("height") = 0,
      "read_frame_calibration(frame, width=0, height=0) -> Calibration: the frame's calibration in its\n"
      "layout's format (KITTI odometry calib.txt and KITTI 2015's per-frame pair included). OSError\n"
      "naming the file when it cannot be read.");
  m.def(
      "sequence_poses",
      [](const std::vector<Frame>& frames, const std::string& posesPath) {
        const sequence::SequencePoses poses = sequence::posesOfSequence(frames, posesPath);
        std::vector<Eigen::Matrix4d> matrices;
        for (const Eigen::Isometry3d& pose : poses.poses) matrices.push_back(pose.matrix());
        return py::make_tuple(matrices, poses.source);
      },
      py::arg("frames"), py::arg("poses") = "",
      "sequence_poses(frames, poses='') -> (list of 4x4 arrays, source): frame i's pose T_world_camera\n"
      "(KITTI odometry: of camera 0), from `poses` (a KITTI poses file) when given, else the sequence's\n"
      "poses.txt, else a raw drive's OXTS packets; `source` says which. ValueError otherwise.");

  py::class_<VoxelMap>(m, "VoxelMap",
                       "The merged map of lidar_sgm_batch -map: one point per occupied voxel, the centroid, mean\n"
                       "color and mean confidence of the points that fell in it; the same clouds in the same\n"
                       "order give the same map, bit for bit.")
      .def(py::init<double>(), py::arg("leaf_size"), "VoxelMap(leaf_size) [m]; ValueError unless positive and finite")
      .def("add", &addToMap, py::arg("points"), py::arg("colors") = py::none(), py::arg("confidence") = py::none(),
           py::arg("to_world") = Eigen::Matrix4d::Identity().eval(),
           "add(points, colors=None, confidence=None, to_world=identity): an (N, 3) cloud (NaN points\n"
           "skipped), its (N, 3) uint8 colors and (N,) confidences when it has them, taken into the world\n"
           "by the 4x4 to_world.")
      .def("__len__", &VoxelMap::size)
      .def_property_readonly("leaf_size", &VoxelMap::leafSize)
      .def_property_readonly("has_color", &VoxelMap::hasColor)
      .def_property_readonly("has_confidence", &VoxelMap::hasConfidence)
      .def("arrays", &mapArrays,
           "arrays() -> (points (N, 3) float32, colors (N, 3) uint8, confidence (N,) float32), one row per voxel\n"
           "in first-occupied order (colors and confidence 0 where the map has none).");
}

}  // namespace python
}  // namespace lidar_sgm
