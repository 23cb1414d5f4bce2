#include "lidar_sgm/eval/groups.hpp"

#include <algorithm>
#include <map>
#include <stdexcept>

#include "lidar_sgm/eval/alpha_sweep.hpp"
#include "lidar_sgm/eval/protocols.hpp"

namespace lidar_sgm {
namespace eval {
namespace {

bool contains(const std::vector<std::string>& list, const std::string& item) {
  return std::find(list.begin(), list.end(), item) != list.end();
}

/// Rejects what would silently select nothing.
void checkNames(const std::vector<std::string>& given, const std::vector<std::string>& known, const char* what) {
  for (const std::string& name : given) {
    if (!contains(known, name)) throw std::invalid_argument(std::string("unknown ") + what + " '" + name + "'");
  }
}

}  // namespace

std::vector<FrameGroup> loadGroups(const GroupSelection& selection) {
  checkNames(selection.protocols, {"P1", "P2", "P3", "KITTI142"}, "protocol");
  checkNames(selection.p3Sets, {"clear64", "rain64", "clear128"}, "P3 set");
  std::vector<FrameGroup> groups;
  if (contains(selection.protocols, "P1")) {
    std::map<std::string, FrameGroup> byKind;
    for (EvalFrame& f : loadP1(selection.dataRoot)) {
      const std::string kind = f.dataset.rfind("kitti", 0) == 0 ? "KITTI" : f.dataset;
      FrameGroup& g = byKind[kind];
      g.name = "P1 " + kind;
      g.description = "GT frames (" + kind + ") with a simulated 64-beam LiDAR sampled from the GT; scored on the other GT pixels";
      g.methods = baseMethods();
      g.frames.push_back(std::move(f));
    }
    for (auto& [kind, g] : byKind) groups.push_back(std::move(g));
  }
  if (contains(selection.protocols, "P2")) {
    FrameGroup g;
    g.name = "P2 real LiDAR";
    g.description = "real KITTI HDL-64 scans: every 4th laser ring held out as GT, the others fed; scored on the held-out rings";
    g.methods = baseMethods();
    g.frames = loadP2(selection.dataRoot);
    if (!g.frames.empty()) groups.push_back(std::move(g));
  }
  if (contains(selection.protocols, "KITTI142")) {
    FrameGroup g;
    g.name = "KITTI142";
    g.description = "the paper's own protocol: KITTI stereo 2015 training frames with the raw Velodyne scan of the same "
                    "instant, scored on every pixel of disp_occ_0 (the input's pixels included, as the paper), split "
                    "by the object map for Table II";
    g.methods = baseMethods();
    g.frames = loadKitti142(selection.dataRoot, selection.kitti142Frames);
    if (!g.frames.empty()) groups.push_back(std::move(g));
  }
  if (contains(selection.protocols, "P3")) {
    struct Variant { const char* key; const char* name; bool rain; int beams; bool third; };
    for (const Variant v : {Variant{"clear64", "P3 clear 64 beams", false, 64, true},
                            Variant{"rain64", "P3 rain 64 beams", true, 64, false},
                            Variant{"clear128", "P3 clear 128 beams", false, 128, false}}) {
      if (!contains(selection.p3Sets, v.key)) continue;
      P3Options o;
      o.frames = selection.synthFrames;
      o.rain = v.rain;
      o.beams = v.beams;
      o.thirdCamera = v.third;
      o.width = selection.synthWidth;
      o.height = selection.synthHeight;
      FrameGroup g;
      g.name = v.name;
      g.description = std::string("synthetic streets with exact GT, ") + (v.rain ? "rain" : "clear") + ", " +
                      std::to_string(v.beams) + "-beam LiDAR" + (v.third ? ", third camera 0.20 m above the left" : "");
      g.methods = baseMethods();
      if (v.third) {
        g.methods.push_back({MethodKind::ThreeCameras, 0.0});
        g.methods.push_back({MethodKind::ThreeCamerasLidar, kPaperAlpha});
      }
      g.frames = loadP3(o);
      groups.push_back(std::move(g));
    }
  }
  return groups;
}

}  // namespace eval
}  // namespace lidar_sgm
