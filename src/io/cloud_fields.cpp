// readCloudFields (cloud_io.hpp): every field of a PCD or PLY file, for readers that need more
// than x, y, z and intensity (the voxel map's colour and confidence).
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "cloud_file.hpp"
#include "cloud_read_error.hpp"
#include "lidar_sgm/io/cloud_io.hpp"
#include "lidar_sgm/io/file_access.hpp"
#include "pcd_reader.hpp"
#include "ply_reader.hpp"

namespace lidar_sgm {
namespace io {
namespace {

int fieldIndex(const pcl::PCLPointCloud2& blob, const std::string& name) {
  for (std::size_t i = 0; i < blob.fields.size(); ++i) {
    if (blob.fields[i].name == name) return static_cast<int>(i);
  }
  return -1;
}

// PLY's red, green, blue (and alpha) bytes as PCL's packed rgb (float) or rgba (uint32) field,
// stored b g r a, as PCL's own PLY reader gives them.
pcl::PCLPointCloud2 packColour(const pcl::PCLPointCloud2& blob) {
  const int channels[4] = {fieldIndex(blob, "blue"), fieldIndex(blob, "green"), fieldIndex(blob, "red"),
                           fieldIndex(blob, "alpha")};
  for (int c = 0; c < 3; ++c) {
    if (channels[c] < 0 || blob.fields[static_cast<std::size_t>(channels[c])].datatype != pcl::PCLPointField::UINT8) {
      return blob;
    }
  }
  const bool alpha =
      channels[3] >= 0 && blob.fields[static_cast<std::size_t>(channels[3])].datatype == pcl::PCLPointField::UINT8;
  pcl::PCLPointCloud2 packed = blob;
  pcl::PCLPointField colour;
  colour.name = alpha ? "rgba" : "rgb";
  colour.datatype = alpha ? pcl::PCLPointField::UINT32 : pcl::PCLPointField::FLOAT32;
  colour.count = 1;
  colour.offset = blob.point_step;
  packed.fields.push_back(colour);
  packed.point_step = blob.point_step + 4;
  packed.row_step = packed.point_step * packed.width;
  const std::size_t points = std::size_t{blob.width} * blob.height;
  packed.data.assign(points * packed.point_step, 0);
  for (std::size_t i = 0; i < points; ++i) {
    const std::uint8_t* from = blob.data.data() + i * blob.point_step;
    std::uint8_t* to = packed.data.data() + i * packed.point_step;
    std::memcpy(to, from, blob.point_step);
    for (int c = 0; c < 4; ++c) {
      to[blob.point_step + c] = c < 3 || alpha ? from[blob.fields[static_cast<std::size_t>(channels[c])].offset] : 255;
    }
  }
  return packed;
}

// An organized PLY's cells in place: a cell without a vertex gets NaN coordinates.
pcl::PCLPointCloud2 placeOnGrid(const detail::PlyContent& content, const pcl::PCLPointCloud2& vertices) {
  pcl::PCLPointCloud2 grid = vertices;
  grid.width = content.gridWidth;
  grid.height = content.gridHeight;
  grid.row_step = grid.point_step * grid.width;
  grid.data.assign(content.grid.size() * grid.point_step, 0);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  for (std::size_t i = 0; i < content.grid.size(); ++i) {
    std::uint8_t* to = grid.data.data() + i * grid.point_step;
    if (content.grid[i] >= 0) {
      std::memcpy(to, vertices.data.data() + static_cast<std::size_t>(content.grid[i]) * grid.point_step,
                  grid.point_step);
      continue;
    }
    for (const pcl::PCLPointField& field : grid.fields) {
      if ((field.name == "x" || field.name == "y" || field.name == "z") && field.datatype == pcl::PCLPointField::FLOAT32) {
        std::memcpy(to + field.offset, &nan, sizeof(nan));
      }
    }
  }
  grid.is_dense = false;
  return grid;
}

}  // namespace

pcl::PCLPointCloud2 readCloudFields(const std::string& path, std::uint64_t maxPoints) {
  detail::requireReadableCloudFile(path);
  const std::string extension = lowerExtension(path);
  if (extension != ".pcd" && extension != ".ply") detail::failCloudRead(path, "expected a .pcd or .ply file");
  const std::uint64_t size = detail::cloudFileSize(path);
  if (size == 0) detail::failCloudRead(path, "the file is empty");
  const std::vector<unsigned char> bytes = detail::readCloudFileBytes(path, size);
  if (extension == ".pcd") return detail::parsePcd(path, bytes.data(), bytes.size(), maxPoints).blob;
  const detail::PlyContent content = detail::parsePly(path, bytes.data(), bytes.size(), maxPoints);
  const pcl::PCLPointCloud2 vertices = packColour(content.blob);
  if (content.grid.empty()) return vertices;
  return placeOnGrid(content, vertices);
}

}  // namespace io
}  // namespace lidar_sgm
