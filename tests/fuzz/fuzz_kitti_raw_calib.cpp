#include "fuzz_input.hpp"
#include "lidar_sgm/io/calibration_io.hpp"

// The two files in one input: calib_cam_to_cam.txt, a NUL byte, calib_velo_to_cam.txt.
extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  const std::size_t split = text.find('\0');
  const std::string camToCam = text.substr(0, split);
  const std::string veloToCam = split == std::string::npos ? std::string() : text.substr(split + 1);
  lidar_sgm::fuzz::expectCleanRefusal([&] { lidar_sgm::io::readKittiRawCalibrationFromString(camToCam, veloToCam); });
  return 0;
}
