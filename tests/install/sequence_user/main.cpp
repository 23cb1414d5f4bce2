// Lists the frames of the folder given (a KITTI layout) and reads each one's calibration.
#include <cstdio>
#include <exception>
#include <vector>

#include <lidar_sgm/sequence/frame_calibration.hpp>
#include <lidar_sgm/sequence/frame_list.hpp>

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: sequence_user FOLDER\n");
    return 2;
  }
  try {
    const std::vector<lidar_sgm::sequence::Frame> frames = lidar_sgm::sequence::framesFromDirectory(argv[1]);
    for (const lidar_sgm::sequence::Frame& frame : frames) {
      const lidar_sgm::geometry::StereoCalibration calibration = lidar_sgm::sequence::readFrameCalibration(frame);
      std::printf("%s: baseline %.3f m\n", frame.name.c_str(), calibration.baseline);
    }
    std::printf("%s: %s, %zu frame(s)\n", argv[1],
                lidar_sgm::sequence::layoutName(lidar_sgm::sequence::directoryLayout(argv[1])), frames.size());
    return frames.empty() ? 1 : 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "Error: %s\n", e.what());
    return 1;
  }
}
