#include "atomic_file.hpp"

#include <unistd.h>

#include <filesystem>
#include <stdexcept>
#include <system_error>

namespace fs = std::filesystem;

namespace lidar_sgm {
namespace io {
namespace detail {

std::string temporaryPathFor(const std::string& path) {
  fs::path temporary(path);
  temporary.replace_filename("." + fs::path(path).stem().string() + ".tmp" + std::to_string(::getpid()) +
                             fs::path(path).extension().string());
  return temporary.string();
}

void commitTemporary(const std::string& temporary, const std::string& path) {
  std::error_code ec;
  fs::rename(temporary, path, ec);
  if (ec) {
    discardTemporary(temporary);
    throw std::runtime_error("cannot write '" + path + "': " + ec.message());
  }
}

void discardTemporary(const std::string& temporary) noexcept {
  std::error_code ignored;
  fs::remove(temporary, ignored);
}

}  // namespace detail
}  // namespace io
}  // namespace lidar_sgm
