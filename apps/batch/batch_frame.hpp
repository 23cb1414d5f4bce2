#pragma once
// One frame of a batch: read, densified as lidar_sgm_densify does, written atomically.

#include <cstddef>
#include <string>

#include "batch/frame_list.hpp"
#include "batch/manifest.hpp"
#include "common/arguments.hpp"

namespace lidar_sgm {
namespace apps {

struct FrameResult {
  std::size_t points = 0;
  FrameTimings ms;
};

/// Densifies `frame` with the method options of `args` (densify_options.hpp) and writes the
/// cloud to `outPath` (.pcd or .ply, -format's encoding) through a temporary file renamed when
/// complete. `width`/`height` is -image_size (0 = from the calibration or the images). Throws
/// (std::exception) naming the file for a missing or bad input, an empty cloud or a failed write;
/// nothing is left at `outPath` then.
FrameResult densifyFrame(const Arguments& args, const Frame& frame, const std::string& outPath, int width,
                         int height);

}  // namespace apps
}  // namespace lidar_sgm
