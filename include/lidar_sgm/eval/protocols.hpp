#pragma once
// The frames of the evaluation protocols P1, P2, P3 (../shared/design/EVALUATION.md), each one
// EvalFrame with every field filled: images, LiDAR input (per pixel and nearest), GT, the input
// pixels that are not scored, f*b and the disparity range.
//
// Shared conventions of the loaders:
// - `exclude` is 1 exactly on the pixels that hold a LiDAR input point (they are not scored).
// - `lidarSparse` holds the nearest input point per pixel (largest x16 disparity).
// - `numDisparities` is 128 unless the GT reaches beyond 120 px; then it is the next multiple of
//   16 above max + 8 (numDisparitiesFor). P2 also counts the input points (same sensor as its GT).
// - Datasets that are absent under the data root are skipped; frames are sorted by dataset name,
//   then frame name.

#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "lidar_sgm/eval/eval_frame.hpp"
#include "lidar_sgm/core/image.hpp"
#include "lidar_sgm/core/lidar_points.hpp"

namespace lidar_sgm {
namespace eval {

/// The folder that holds the third-party datasets: `option` when not empty (the tools' -data),
/// else $LIDAR_SGM_DATA when set and not empty, else "../shared/data" relative to the working
/// directory (the data beside the repository, run from its root). A run-time choice, never a
/// path fixed at build time: an installed tool has no source tree beside it.
std::string resolveDataRoot(const std::string& option = "");

/// f*b used for KITTI frames without a calibration file (stereo 2012/2015, the sparse sample):
/// KITTI 2015's rectified focal length and its ~0.54 m baseline (2012's f is 707 px: ~2 % off,
/// which only IP-Basic's depth <-> disparity round trip sees, and it inverts it again).
constexpr double kKittiFocalBaseline = 721.5377 * 0.54;
/// DrivingStereo (half resolution): fx ~ 1003.6 px, baseline ~ 0.545 m (its SOURCE.md); GT
/// 4.6..81.8 px -> 6.7..119 m.
constexpr double kDrivingStereoFocalBaseline = 1003.6 * 0.545;
/// Middlebury has no metric scale that matters here; 200 px*m puts its GT (4.5..108.5 px) at
/// 1.8..44 m, inside IP-Basic's 0.1..100 m depth range.
constexpr double kMiddleburyFocalBaseline = 200.0;

/// The search range for a frame whose largest disparity is `maxDisparity` [px]: 128, or the next
/// multiple of 16 above maxDisparity + 8 when that exceeds 128.
int numDisparitiesFor(double maxDisparity);

/// Fills lidar, lidarSparse (nearest per pixel) and exclude (1 on every pixel with an input
/// point) of `frame` from `input`.
void setLidarInput(EvalFrame& frame, const LidarPoints& input);

/// The largest disparity [px] of the GT (0 where there is none).
double maxGroundTruth(const Image<float>& groundTruth);

// ---------------------------------------------------------------------------------------------
// P1: GT frames with a simulated 64-beam LiDAR (eval::simulateLidarFromGroundTruth with its
// default options, as tests/eval/test_kitti_p1.cpp): kitti2015, kitti2012, drivingstereo,
// middlebury (5 scenes; GT value/4 for the 2003 quarter-size scenes, value/2 for the 2005/6
// half-size ones). `dataRoot` is the folder that holds the datasets (../shared/data).
std::vector<EvalFrame> loadP1(const std::string& dataRoot);

// ---------------------------------------------------------------------------------------------
// KITTI142: the paper's own protocol (Sec. IV-A-a, Tables I and II) on kitti2015_lidar: KITTI
// stereo 2015 training frames with the raw scan of the same instant (29 of the paper's 142 in
// ../shared/data). The input is the whole scan projected as the tools project it; every pixel of
// disp_occ_0 is scored (exclude empty, as the paper), inputPixels marks the input's pixels for the
// "no input point" figure, objectMap is obj_map (Table II's background / foreground split).
// `maxFrames` > 0 keeps the first frames (by id) only. No frame when the folder is absent.
std::vector<EvalFrame> loadKitti142(const std::string& dataRoot, int maxFrames = 0);

// ---------------------------------------------------------------------------------------------
// P2: real LiDAR, ring hold-out.
// - kitti_stereo_lidar_calib_nogt (dataset "kitti_lidar", 2 frames): each point's laser ring is
//   recovered (lidar_rings.hpp); rings with ring % 4 == 3 are held out as GT, the others are the
//   input. The input is projected as the tools would (geometry::project, default options,
//   occlusion filter on). The GT is the held-out points that survive the same projection of the
//   whole scan: the occlusion filter then sees the neighbouring rings too (above and below a GT
//   ring are input rings), so it removes more of the GT points the camera cannot see than on
//   the held-out rings alone. GT disparity = the nearest held-out point per pixel.
// - kitti_stereo_sparse_lidar_disparity_sample (dataset "kitti_sparse", 1 frame "sample"): the
//   LiDAR is already a sparse disparity image; its image rows with >= 20 points are numbered top
//   to bottom and those with index % 4 == 3 are held out as GT (splitSparseRows).
std::vector<EvalFrame> loadP2(const std::string& dataRoot);

/// A scan split by ring for P2.
struct RingSplit {
  std::vector<Eigen::Vector3f> input;     ///< points of the rings that are fed
  std::vector<Eigen::Vector3f> heldOut;   ///< points of the rings that are the GT
  std::vector<int> inputRings;            ///< ring of each input point
  std::vector<int> heldOutRings;          ///< ring of each held-out point
  std::vector<std::size_t> heldOutIndex;  ///< index of each held-out point in the scan
  int rings = 0;
};
/// Holds out the rings with ring % period == phase.
RingSplit splitByRing(const std::vector<Eigen::Vector3f>& points, const std::vector<int>& rings, int period = 4,
                      int phase = 3);

/// The row hold-out of a sparse disparity image (x16, kInvalidDisparity = none): rows with at
/// least `minPointsPerRow` points are numbered from the top; those with index % period == phase
/// go to `heldOut`, every other point to `input`. Both outputs have the input's size.
void splitSparseRows(const Image<std::int16_t>& sparse, Image<std::int16_t>& input, Image<std::int16_t>& heldOut,
                     int minPointsPerRow = 20, int period = 4, int phase = 3);

// ---------------------------------------------------------------------------------------------
// P3: synthetic frames of the project's own generator (synth::renderFrame) with exact dense GT.
struct P3Options {
  int frames = 10;
  std::uint32_t firstSeed = 100;  ///< frame i has seed firstSeed + i
  bool rain = false;
  int beams = 64;                 ///< 64 or 128
  bool thirdCamera = false;
  int width = 1242, height = 375;
};
/// The scan is projected with the calibration as written (synth::kittiCalibrationText through a
/// temporary file and io::readKittiCalibration), default projection options. Dataset
/// "synth_<clear|rain>_<64|128>[_3cam]", frame names = the seed, 6 digits.
std::vector<EvalFrame> loadP3(const P3Options& options);
/// "synth_<clear|rain>_<64|128>[_3cam]".
std::string p3DatasetName(const P3Options& options);

}  // namespace eval
}  // namespace lidar_sgm
