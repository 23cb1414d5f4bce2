#pragma once
/// @file atomic_file.hpp  (private) Write-then-rename: an output file appears only complete.

#include <string>

namespace lidar_sgm {
namespace io {
namespace detail {

/// A hidden temporary name in the same directory as `path` (so rename is atomic), keeping the
/// extension (writers that choose the format by extension still work): dir/.stem.tmpPID.ext
std::string temporaryPathFor(const std::string& path);

/// Renames `temporary` over `path`; on failure removes `temporary` and throws
/// std::runtime_error("cannot write 'path': reason").
void commitTemporary(const std::string& temporary, const std::string& path);

/// Removes `temporary` if it exists; never throws (for error paths).
void discardTemporary(const std::string& temporary) noexcept;

}  // namespace detail
}  // namespace io
}  // namespace lidar_sgm
