#pragma once
/// @file group_run.hpp  One table of the evaluation: the frames of one protocol on one kind of
/// data, every method and the alpha sweep on each frame, medians over the frames.

#include <string>
#include <vector>

#include "lidar_sgm/core/matcher.hpp"
#include "lidar_sgm/core/parameters.hpp"
#include "lidar_sgm/eval/eval_frame.hpp"
#include "lidar_sgm/eval/methods.hpp"
#include "lidar_sgm/eval/report.hpp"

namespace lidar_sgm {
namespace eval {

/// The frames of one table (medians never mix kinds of data).
struct FrameGroup {
  std::string name;         ///< "P1 KITTI", "P3 rain 64 beams", ...
  std::string description;
  std::vector<EvalFrame> frames;
  std::vector<Method> methods;  ///< besides the alpha sweep of LiDAR-SGM
};

/// What every group is compared on: stereo-only, LiDAR-only, OpenCV SGBM, IP-Basic.
std::vector<Method> baseMethods();

struct GroupRunOptions {
  std::vector<double> alphas;  ///< the sweep of the fused method (sweepAlphas); should hold kPaperAlpha
  int threads = 1;             ///< in all: frames in parallel, each frame's matcher an equal share of the rest
  std::string picturesDir;     ///< per-frame pictures go here; empty: none
  /// The LiDAR-SGM methods' configuration (alpha, numDisparities and threads are set per run):
  /// the tools' default unless the evaluation's options say otherwise.
  DensifierConfig config;
  /// The fixed search range's numDisparities (config.rangeMode Fixed, or a frame without
  /// LiDAR); 0 = the frame's (the protocol's, from its GT: docs/EVALUATION.md).
  int fixedNumDisparities = 0;
};

/// Runs every method of `group` and the fused method at every alpha on each frame, in parallel
/// (the matchers' results do not depend on their thread count, so neither does the result).
/// The result holds, per frame, the group's methods, the fused method at kPaperAlpha and at the
/// sweep's best alpha (bestAlpha set), and the sweep's medians. Throws std::runtime_error naming
/// the group and frame when a frame fails.
ProtocolResult runGroup(const FrameGroup& group, const GroupRunOptions& options);

/// `text` in lower case with every other character than a letter or digit as '_' (file names).
std::string slug(const std::string& text);

}  // namespace eval
}  // namespace lidar_sgm
