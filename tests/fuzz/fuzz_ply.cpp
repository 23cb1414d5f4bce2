#include "fuzz_input.hpp"
#include "lidar_sgm/io/cloud_io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  lidar_sgm::fuzz::expectCleanRefusal([&] { lidar_sgm::io::readPlyFromBuffer(data, size, "fuzz.ply"); });
  return 0;
}
