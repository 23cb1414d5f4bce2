#include <cstdio>

#include "fuzz_input.hpp"
#include "lidar_sgm/io/image_io.hpp"

// The image readers take a path: the input goes through a file. Each of them reads it, as the
// tools do for the stereo pair, the disparity ground truth and the depth maps.
extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = lidar_sgm::fuzz::writeInput(data, size, ".png");
  lidar_sgm::fuzz::expectCleanRefusal([&] { lidar_sgm::io::readImage(path); });
  lidar_sgm::fuzz::expectCleanRefusal([&] { lidar_sgm::io::readKittiDisparity(path); });
  lidar_sgm::fuzz::expectCleanRefusal([&] { lidar_sgm::io::readKittiDepthAsDisparity(path, 389.0); });
  std::remove(path.c_str());
  return 0;
}
