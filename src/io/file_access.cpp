#include "lidar_sgm/io/file_access.hpp"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <filesystem>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace lidar_sgm {
namespace io {

std::string unreadableFileReason(const std::string& path) {
  struct stat status {};
  if (::stat(path.c_str(), &status) != 0) {
    const int error = errno;
    if (error == ENOENT) return "no such file";
    // ENOTDIR: a folder of the path is a file; EACCES: a folder may not be searched.
    return std::string("cannot reach it: ") + std::strerror(error);
  }
  if (S_ISDIR(status.st_mode)) return "it is a directory, not a file";
  if (!S_ISREG(status.st_mode)) return "not a regular file (a device, pipe or socket)";
  // Opening is the only reliable test (ACLs, root, read-only mounts): access() would guess.
  const int descriptor = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (descriptor < 0) return std::string("cannot open it: ") + std::strerror(errno);
  ::close(descriptor);
  return "";
}

std::string lowerExtension(const std::string& path) {
  std::string extension = std::filesystem::path(path).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return extension;
}

}  // namespace io
}  // namespace lidar_sgm
