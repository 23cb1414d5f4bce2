#pragma once
/// @file pcl_file_writer.hpp  (private) PCL's file writers, every byte of their output checked.
///
/// Why: PCL's ASCII PCD and PLY writers write through an std::ofstream whose errors they never
/// check, so on a full disk they return success for a truncated file. Here they write into an
/// anonymous memory file (memfd), which a full disk cannot cut short, and its bytes are then
/// copied into the output through io::AtomicFile, whose every write is checked. A memory file
/// obeys a file size limit (RLIMIT_FSIZE) too, and PCL would not say that it was cut short
/// either: so what PCL wrote is read back whole by our strict reader before it is copied.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>

#include "lidar_sgm/io/atomic_file.hpp"

namespace lidar_sgm {
namespace io {
namespace detail {

/// Calls `write(file)` with the name of an anonymous memory file ("/proc/self/fd/N"); `write`
/// returns PCL's status (0 = success). Then `verify(bytes, size)` reads what it wrote (throwing
/// when it is not whole), and the bytes are appended to `out`. Throws std::runtime_error with the
/// reason (PCL's failure, the check's, or the memory file's or `out`'s error).
void writeThroughPcl(AtomicFile& out, const std::function<int(const std::string& file)>& write,
                     const std::function<void(const std::uint8_t* bytes, std::size_t size)>& verify);

}  // namespace detail
}  // namespace io
}  // namespace lidar_sgm
