// write_cloud: a DensifyResult's cloud to PCD / PLY, as lidar_sgm_densify writes its OUTPUT: the
// same point types (x y z, rgb with colors, confidence unless no_confidence), the same writer
// (io::writeCloud: a temporary file renamed into place when complete) and the same -format names.
#include <cstdint>
#include <string>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include "bindings.hpp"
#include "densify_result.hpp"
#include "errors.hpp"
#include "lidar_sgm/io/cloud_io.hpp"
#include "lidar_sgm/pcl/point_types.hpp"

namespace lidar_sgm {
namespace python {

namespace py = pybind11;

namespace {

template <typename T>
using Contiguous = py::array_t<T, py::array::c_style | py::array::forcecast>;

/// The result's arrays, checked against its points, and raw pointers to them for writing without
/// the GIL (the arrays stay alive here).
struct ResultArrays {
  Contiguous<float> points;
  Contiguous<std::uint8_t> colors;
  Contiguous<float> confidence;
  bool hasColors = false;
  bool hasConfidence = false;
  std::size_t size = 0;

  explicit ResultArrays(const DensifyResult& r)
      : points(Contiguous<float>::ensure(r.points)),
        hasColors(!r.colors.is_none()),
        hasConfidence(!r.pointConfidence.is_none()) {
    if (!points || points.ndim() != 2 || points.shape(1) != 3) throw std::invalid_argument("result.points must be (M, 3)");
    size = static_cast<std::size_t>(points.shape(0));
    if (hasColors) {
      colors = Contiguous<std::uint8_t>::ensure(r.colors);
      if (!colors || colors.ndim() != 2 || colors.shape(1) != 3 || static_cast<std::size_t>(colors.shape(0)) != size) {
        throw std::invalid_argument("result.colors must be (M, 3), one row per point");
      }
    }
    if (hasConfidence) {
      confidence = Contiguous<float>::ensure(r.pointConfidence);
      if (!confidence || confidence.ndim() != 1 || static_cast<std::size_t>(confidence.shape(0)) != size) {
        throw std::invalid_argument("result.point_confidence must be (M,), one value per point");
      }
    }
  }
};

/// The cloud of the tool's point type PointT (pcl/point_types.hpp for the confidence ones).
template <typename PointT>
pcl::PointCloud<PointT> cloudOf(const ResultArrays& a, const DensifyResult& r) {
  pcl::PointCloud<PointT> cloud;
  cloud.resize(a.size);
  const float* p = a.points.data();
  for (std::size_t i = 0; i < a.size; ++i) {
    PointT& q = cloud[i];
    q.x = p[3 * i];
    q.y = p[3 * i + 1];
    q.z = p[3 * i + 2];
    if constexpr (pcl::traits::has_color_v<PointT>) {
      const std::uint8_t* c = a.colors.data() + 3 * i;
      q.r = c[0];
      q.g = c[1];
      q.b = c[2];
    }
    if constexpr (pcl::traits::has_field<PointT, pcl::fields::confidence>::value) q.confidence = a.confidence.data()[i];
  }
  // The organized grid (keep_organized) when the result still has its shape, else one row.
  const bool organized = r.width > 0 && r.height > 0 && static_cast<std::size_t>(r.width) * r.height == a.size;
  cloud.width = organized ? static_cast<std::uint32_t>(r.width) : static_cast<std::uint32_t>(a.size);
  cloud.height = organized ? static_cast<std::uint32_t>(r.height) : 1;
  cloud.is_dense = r.isDense;
  return cloud;
}

template <typename PointT>
void write(const std::string& path, const ResultArrays& a, const DensifyResult& r, io::CloudFormat format) {
  const pcl::PointCloud<PointT> cloud = cloudOf<PointT>(a, r);
  py::gil_scoped_release release;
  readingFile([&] { io::writeCloud(path, cloud, format); });
}

void writeCloud(const py::object& pathLike, const DensifyResult& result, const std::string& formatName) {
  const std::string path = py::str(py::module_::import("os").attr("fspath")(pathLike));
  io::CloudFormat format;
  try {
    format = io::cloudFormatFromString(formatName);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(std::string("format: ") + e.what());
  }
  io::checkCloudOutput(path, format);
  const ResultArrays a(result);
  if (a.hasConfidence) {
    a.hasColors ? write<PointXYZRGBConfidence>(path, a, result, format) : write<PointXYZConfidence>(path, a, result, format);
  } else {
    a.hasColors ? write<pcl::PointXYZRGB>(path, a, result, format) : write<pcl::PointXYZ>(path, a, result, format);
  }
}

}  // namespace

void bindCloudWriter(py::module_& m) {
  m.def("write_cloud", &writeCloud, py::arg("path"), py::arg("result"), py::arg("format") = "binary",
        "write_cloud(path, result, format='binary')\n\n"
        "Writes a DensifyResult's cloud as lidar_sgm_densify writes OUTPUT, with the same code: .pcd or .ply by\n"
        "the extension; x y z, rgb when it has colors, and confidence in [0, 1] unless no_confidence.\n"
        "format: 'binary', 'ascii' or 'compressed' (PCD only), as the tool's -format. The file is written\n"
        "to a temporary beside it and renamed into place when complete: an existing file is replaced\n"
        "whole or not at all. ValueError for another extension or format, OSError when it cannot be written.");
}

}  // namespace python
}  // namespace lidar_sgm
