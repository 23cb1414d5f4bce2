// The files the tools read, as numpy arrays: KITTI .bin, PCD / PLY clouds, images.
#include <cstring>
#include <string>

#include <opencv2/imgproc.hpp>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include "arrays.hpp"
#include "bindings.hpp"
#include "errors.hpp"
#include "lidar_sgm/io/cloud_io.hpp"
#include "lidar_sgm/io/image_io.hpp"
#include "lidar_sgm/io/kitti_bin.hpp"

namespace lidar_sgm {
namespace python {

namespace py = pybind11;

namespace {

/// x, y, z, intensity per point: a pcl::PointXYZI cloud, or KITTI points read without PCL.
template <typename Points>
py::array_t<float> cloudArray(const Points& cloud) {
  py::array_t<float> out = newArray<float>(cloud.size(), 4);
  float* o = out.mutable_data();
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const auto& p = cloud[i];
    o[4 * i] = p.x;
    o[4 * i + 1] = p.y;
    o[4 * i + 2] = p.z;
    o[4 * i + 3] = p.intensity;
  }
  return out;
}

py::array imageArray(const cv::Mat& bgr) {
  cv::Mat image = bgr;
  if (image.channels() == 3) cv::cvtColor(image, image, cv::COLOR_BGR2RGB);
  if (image.channels() == 4) cv::cvtColor(image, image, cv::COLOR_BGRA2RGB);
  const py::dtype dtype = image.depth() == CV_16U ? py::dtype::of<std::uint16_t>() : py::dtype::of<std::uint8_t>();
  std::vector<py::ssize_t> shape{image.rows, image.cols};
  if (image.channels() == 3) shape.push_back(3);
  py::array out(dtype, shape);
  const std::size_t rowBytes = image.cols * image.elemSize();
  auto* o = static_cast<std::uint8_t*>(out.mutable_data());
  for (int y = 0; y < image.rows; ++y) std::memcpy(o + rowBytes * static_cast<std::size_t>(y), image.ptr(y), rowBytes);
  return out;
}

}  // namespace

void bindIo(py::module_& m) {
  m.def(
      "read_kitti_bin", [](const std::string& path) { return cloudArray(readingFile([&] { return io::readKittiScan(path); })); },
      py::arg("path"),
      "read_kitti_bin(path) -> (N, 4) float32 array: x, y, z [m], reflectance (KITTI velodyne .bin).\n"
      "OSError for a missing file or one whose size is not a multiple of 16 bytes.");
  m.def(
      "read_cloud", [](const std::string& path) { return cloudArray(readingFile([&] { return io::readCloud(path); })); },
      py::arg("path"),
      "read_cloud(path) -> (N, 4) float32 array: x, y, z, intensity (0 without one), as the tools read\n"
      "INPUT: .bin (KITTI), .pcd or .ply. OSError for another extension or a bad file.");
  m.def(
      "read_image", [](const std::string& path) { return imageArray(readingFile([&] { return io::readImage(path); })); },
      py::arg("path"),
      "read_image(path) -> (H, W) gray or (H, W, 3) RGB array, uint8 or uint16, as stored (alpha dropped):\n"
      "what Densifier.densify and match take for left / right. OSError for a missing or unreadable file.");
}

}  // namespace python
}  // namespace lidar_sgm
