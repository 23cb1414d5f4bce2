// checkCloudFile (cloud_io.hpp): a .pcd or .ply file is whole when our parsers, which check the
// body against the header (and every ASCII value), accept it; nothing is converted.
#include <cstdint>
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

void checkCloudFile(const std::string& path) {
  detail::requireReadableCloudFile(path);
  const std::string extension = lowerExtension(path);
  if (extension != ".pcd" && extension != ".ply") detail::failCloudRead(path, "expected a .pcd or .ply file");
  const std::uint64_t size = detail::cloudFileSize(path);
  if (size == 0) detail::failCloudRead(path, "the file is empty");
  const std::vector<unsigned char> bytes = detail::readCloudFileBytes(path, size);
  if (extension == ".pcd") {
    detail::parsePcd(path, bytes.data(), bytes.size(), kMaxCloudPoints);
  } else {
    detail::parsePly(path, bytes.data(), bytes.size(), kMaxCloudPoints);
  }
}

}  // namespace io
}  // namespace lidar_sgm
