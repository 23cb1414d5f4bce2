#include "kitti2015_layout.hpp"

#include <cctype>
#include <stdexcept>
#include <string>
#include <system_error>

#include "frame_folders.hpp"

namespace fs = std::filesystem;

namespace lidar_sgm {
namespace sequence {
namespace detail {
namespace {

const char* const kCamToCam = "calib_cam_to_cam";
const char* const kVeloToCam = "calib_velo_to_cam";

/// What KITTI 2015 looks like, for messages.
const char* const kLookedFor =
    "looked for calib/calib_cam_to_cam.txt with calib/calib_velo_to_cam.txt (KITTI raw format, one pair for "
    "every frame) and for calib_cam_to_cam/NNNNNN.txt with calib_velo_to_cam/NNNNNN.txt (KITTI stereo 2015's "
    "own, per frame; NNNNNN_10.txt too)";

/// KITTI 2015 names a frame NNNNNN_10 (and its successor image NNNNNN_11).
bool isFrameStem(const std::string& stem) {
  if (stem.size() != 9 || stem.compare(6, 3, "_10") != 0) return false;
  for (std::size_t i = 0; i < 6; ++i) {
    if (std::isdigit(static_cast<unsigned char>(stem[i])) == 0) return false;
  }
  return true;
}

bool hasFrameNamedScan(const fs::path& velodyne) {
  std::error_code ec;
  for (fs::directory_iterator it(velodyne, ec), end; !ec && it != end; it.increment(ec)) {
    if (isFrameStem(it->path().stem().string())) return true;
  }
  return false;
}

/// The per-frame calibration files are numbered by the frame's id without "_10" (000007.txt for
/// 000007_10); the frame's full stem is taken too. Neither there: the id's, so that the frame
/// fails naming the file KITTI 2015 has.
fs::path perFrameFile(const fs::path& folder, const std::string& stem) {
  const std::string id = isFrameStem(stem) ? stem.substr(0, 6) : stem;
  const fs::path full = folder / (stem + ".txt");
  return !isFile(folder / (id + ".txt")) && isFile(full) ? full : folder / (id + ".txt");
}

/// One of a pair present without the other: a layout error, named before any frame runs.
void requireBoth(const fs::path& dir, const std::string& a, bool aThere, const std::string& b, bool bThere) {
  if (aThere == bThere) return;
  throw std::invalid_argument("-input_dir '" + dir.string() + "' (KITTI stereo 2015) has " + (aThere ? a : b) +
                              " but no " + (aThere ? b : a) + ": the calibration needs both");
}

}  // namespace

bool isKittiStereo2015(const fs::path& dir) {
  if (!isDirectory(dir / "velodyne")) return false;
  return isDirectory(dir / kCamToCam) || isDirectory(dir / kVeloToCam) ||
         isFile(dir / "calib" / "calib_cam_to_cam.txt") || isFile(dir / "calib" / "calib_velo_to_cam.txt") ||
         hasFrameNamedScan(dir / "velodyne");
}

std::vector<Frame> kittiStereo2015Frames(const fs::path& dir) {
  const fs::path camFolder = dir / kCamToCam;
  const fs::path veloFolder = dir / kVeloToCam;
  // KITTI 2015's own files, when there, win over a shared pair: each is its frame's recording
  // day's calibration, while the shared pair is right only where every frame is of one day.
  const bool perFrame = isDirectory(camFolder) || isDirectory(veloFolder);
  const fs::path sharedCam = dir / "calib" / "calib_cam_to_cam.txt";
  const fs::path sharedVelo = dir / "calib" / "calib_velo_to_cam.txt";
  if (perFrame) {
    requireBoth(dir, "calib_cam_to_cam/", isDirectory(camFolder), "calib_velo_to_cam/", isDirectory(veloFolder));
  } else if (isFile(sharedCam) || isFile(sharedVelo)) {
    requireBoth(dir, "calib/calib_cam_to_cam.txt", isFile(sharedCam), "calib/calib_velo_to_cam.txt",
                isFile(sharedVelo));
  } else {
    throw std::invalid_argument("-input_dir '" + dir.string() +
                                "' has KITTI stereo 2015's scans (velodyne/NNNNNN_10) but no calibration: " +
                                kLookedFor);
  }
  // Only scans make frames: KITTI 2015's image_2/ also holds the _11 images (no scan of their
  // instant), and only some frames have a raw scan at all.
  // Shared: io::readCalibration reads calib_cam_to_cam.txt with calib_velo_to_cam.txt beside it,
  // as lidar_sgm_densify -calib calib/calib_cam_to_cam.txt does (the same clouds).
  const auto calibOf = [&](const std::string& stem) {
    return (perFrame ? perFrameFile(camFolder, stem) : sharedCam).string();
  };
  std::vector<Frame> frames =
      framesOf(dir / "velodyne", dir / "image_2", dir / "image_3", "",
               perFrame ? CalibrationFormat::KittiRawPair : CalibrationFormat::Auto, MissingScans::Ignored, calibOf);
  if (perFrame) {
    for (Frame& frame : frames) {
      frame.veloToCam = perFrameFile(veloFolder, fs::path(frame.scan).stem().string()).string();
    }
  }
  return frames;
}

}  // namespace detail
}  // namespace sequence
}  // namespace lidar_sgm
