#pragma once
/// @file cloud_file.hpp  (private) How every cloud reader gets at a file: the same checks, in the
/// same order, and the same messages ("cannot read cloud '<path>': <problem>") for .bin, .pcd and
/// .ply. No PCL: the KITTI reader uses it too.

#include <cstdint>
#include <string>
#include <vector>

namespace lidar_sgm {
namespace io {
namespace detail {

/// Throws unless `path` is a regular file this process can open (unreadableFileReason's words).
void requireReadableCloudFile(const std::string& path);

/// The file's size in bytes; throws with the system's reason when it cannot be had.
std::uint64_t cloudFileSize(const std::string& path);

/// All `size` bytes of the file (its size, checked by the caller first: a reader refuses a file
/// by its size before loading it). Throws when it cannot be opened or holds fewer bytes.
std::vector<unsigned char> readCloudFileBytes(const std::string& path, std::uint64_t size);

}  // namespace detail
}  // namespace io
}  // namespace lidar_sgm
