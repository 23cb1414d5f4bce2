#pragma once
/// @file file_access.hpp  Why an input file cannot be read, in words a user can act on: every
/// reader (images, calibration, clouds) and the tools' list files say the same thing.

#include <string>

namespace lidar_sgm {
namespace io {

/// "" when `path` is a regular file this process can open for reading; otherwise the reason:
/// "no such file", "it is a directory, not a file", "not a regular file (...)", or the system's
/// reason for refusing to open it (e.g. "cannot open it: Permission denied", from errno).
std::string unreadableFileReason(const std::string& path);

/// The extension of `path`'s file name in lower case, with its dot (".pcd"); "" when it has none.
std::string lowerExtension(const std::string& path);

}  // namespace io
}  // namespace lidar_sgm
