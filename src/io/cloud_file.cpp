#include "cloud_file.hpp"

#include <filesystem>
#include <fstream>
#include <system_error>

#include "cloud_read_error.hpp"
#include "lidar_sgm/core/huge_page_allocator.hpp"
#include "lidar_sgm/io/file_access.hpp"

namespace lidar_sgm {
namespace io {
namespace detail {

void requireReadableCloudFile(const std::string& path) {
  const std::string unreadable = unreadableFileReason(path);
  if (!unreadable.empty()) failCloudRead(path, unreadable);
}

std::uint64_t cloudFileSize(const std::string& path) {
  std::error_code ec;
  const std::uint64_t size = std::filesystem::file_size(path, ec);
  if (ec) failCloudRead(path, ec.message());
  return size;
}

std::vector<unsigned char> readCloudFileBytes(const std::string& path, std::uint64_t size) {
  std::vector<unsigned char> bytes;
  reserveOnHugePages(bytes, static_cast<std::size_t>(size));
  bytes.resize(static_cast<std::size_t>(size));
  std::ifstream in(path, std::ios::binary);
  if (!in) failCloudRead(path, "cannot open the file");
  in.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  const auto got = static_cast<std::uint64_t>(in.gcount());
  if (got != size) {
    failCloudRead(path, "read error after " + std::to_string(got) + " of " + std::to_string(size) + " bytes");
  }
  return bytes;
}

}  // namespace detail
}  // namespace io
}  // namespace lidar_sgm
