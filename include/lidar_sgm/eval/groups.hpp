#pragma once
/// @file groups.hpp  Which frames form which table: P1 per kind of data, P2, and the P3 sets.

#include <string>
#include <vector>

#include "lidar_sgm/eval/group_run.hpp"

namespace lidar_sgm {
namespace eval {

struct GroupSelection {
  std::string dataRoot = "../shared/data";                         ///< see resolveDataRoot
  std::vector<std::string> protocols{"P1", "P2", "KITTI142", "P3"};  ///< subset of P1, P2, KITTI142, P3
  std::vector<std::string> p3Sets{"clear64", "rain64", "clear128"};  ///< clear64 has the third camera
  int synthFrames = 10;                                            ///< per P3 set, seeds 100..
  int synthWidth = 1242, synthHeight = 375;
  int kitti142Frames = 0;                                          ///< KITTI142: the first N frames, 0 = all
};

/// The groups of `selection`, in the order P1 (one group per kind: "KITTI" for KITTI 2012 and
/// 2015 together, then each other dataset), P2, KITTI142, P3 (clear64, rain64, clear128). A protocol whose
/// data is absent under the data root gives no group (P1 kinds, P2); P3 is rendered. Every group
/// has baseMethods(); P3 clear64 adds the Triple-SGM methods. Throws std::invalid_argument for
/// an unknown protocol or P3 set.
std::vector<FrameGroup> loadGroups(const GroupSelection& selection);

}  // namespace eval
}  // namespace lidar_sgm
