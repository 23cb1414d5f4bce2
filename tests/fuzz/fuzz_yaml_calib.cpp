#include "fuzz_input.hpp"
#include "lidar_sgm/io/calibration_io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  lidar_sgm::fuzz::expectCleanRefusal([&] { lidar_sgm::io::readCalibrationYamlFromString(text, "fuzz.yaml"); });
  return 0;
}
