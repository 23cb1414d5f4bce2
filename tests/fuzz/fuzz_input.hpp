#pragma once
// What every fuzz target shares: a reader that refuses its input must do so with the library's
// documented exceptions; anything else (a crash, another exception) is a finding.

#include <cstddef>
#include <cstdint>
#include <fstream>
#include <stdexcept>
#include <string>
#include <unistd.h>

namespace lidar_sgm {
namespace fuzz {

/// Runs `read`; std::runtime_error and std::invalid_argument are clean refusals.
template <typename Read>
void expectCleanRefusal(Read read) {
  try {
    read();
  } catch (const std::runtime_error&) {
  } catch (const std::invalid_argument&) {
  }
}

/// The readers that take a path get the input through a file of this process, named `suffix`.
inline std::string writeInput(const std::uint8_t* data, std::size_t size, const std::string& suffix) {
  const std::string path = "/tmp/lidar_sgm_fuzz_" + std::to_string(::getpid()) + suffix;
  std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  return path;
}

}  // namespace fuzz
}  // namespace lidar_sgm
