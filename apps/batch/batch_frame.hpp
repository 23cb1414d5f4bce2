#pragma once
// One frame of a batch: read, densified as lidar_sgm_densify does, written atomically.

#include <cstddef>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "lidar_sgm/sequence/frame_list.hpp"
#include "lidar_sgm/sequence/manifest.hpp"
#include "common/arguments.hpp"
#include "densify/densify_options.hpp"
#include "lidar_sgm/pipeline/densifier_config.hpp"

namespace lidar_sgm {
namespace apps {

struct FrameResult {
  std::size_t points = 0;
  std::uintmax_t bytes = 0;  ///< the written cloud's file size
  sequence::FrameTimings ms;
};

/// The image size a calibration file is used with, and the image that fixed it.
struct CalibrationImage {
  int width = 0;
  int height = 0;
  std::string image;
};

/// For each calibration file that two or more of `frames` share (a sequence's calib.txt), the size
/// of the first of their left images (in `frames` order) whose size can be read (io::imageSize: a
/// PNG's from its header, without decoding it). One calibration fits one image size: a frame of
/// another size is refused rather than densified with intrinsics that are not its own (KITTI's
/// odometry calib.txt carries no size to check against).
std::map<std::string, CalibrationImage> sharedCalibrationImages(const std::vector<sequence::Frame>& frames);

/// Densifies frames one after another with one configuration (the option table's, read once),
/// keeping one SGMDensification per output point type so that the matcher's buffers are
/// allocated once per worker, not once per frame (the result does not depend on it: every
/// buffer is written before it is read, and each frame's setInputCloud() drops the images of
/// the frame before). Not thread-safe: one per worker thread.
class FrameDensifier {
 public:
  /// `config` is the Densifier's configuration and `args` the tool's own options (-format,
  /// -voxel, -max_points); `width`/`height` is -image_size (0 = from the calibration or the
  /// images); `threads` the matcher's threads for this worker (never changes a result); `shared`
  /// is sharedCalibrationImages() of the whole sequence.
  FrameDensifier(const Arguments& args, const DensifierConfig& config, int width, int height, int threads,
                 std::map<std::string, CalibrationImage> shared);
  ~FrameDensifier();
  FrameDensifier(const FrameDensifier&) = delete;
  FrameDensifier& operator=(const FrameDensifier&) = delete;

  /// Densifies `frame` and writes the cloud to `outPath` (.pcd or .ply, -format's encoding)
  /// through a temporary file renamed when complete. Throws (std::exception) naming the file for
  /// a missing or bad input, an empty cloud or a failed write; nothing is left at `outPath` then.
  FrameResult densify(const sequence::Frame& frame, const std::string& outPath);

 private:
  struct Densifications;
  DensifierConfig config_;  ///< with this worker's threads
  OutputOptions out_;
  std::uint64_t maxPoints_;
  int width_;
  int height_;
  std::map<std::string, CalibrationImage> shared_;
  std::unique_ptr<Densifications> densifications_;
};

}  // namespace apps
}  // namespace lidar_sgm
