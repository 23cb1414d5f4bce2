#pragma once
// The batch's frames run on worker threads, each frame whole on one worker (load, match, save),
// so that one frame's reading and writing overlap another's matching and the serial parts of a
// frame run side by side; their records come back on the calling thread in frame order, so the
// manifest and the log read the same whatever the number of workers.

#include <cstddef>
#include <functional>

#include "lidar_sgm/sequence/manifest.hpp"

namespace lidar_sgm {
namespace sequence {

/// Does frame `index` on worker `worker` (0 <= worker < jobs) and returns its record; must not
/// throw for a frame's own failure (that is a "failed" record).
using FrameWork = std::function<FrameRecord(std::size_t index, int worker)>;
/// Receives frame `index`'s record, on the calling thread, in frame order.
using FrameDone = std::function<void(std::size_t index, const FrameRecord& record)>;
/// Asked before a worker takes its next frame: true stops the run.
using StopAsked = std::function<bool()>;

/// Runs frames 0..count-1 on `jobs` worker threads (jobs >= 1; 1 runs them on one worker thread
/// as well). Workers take frames in order, and every frame taken is finished, so when `stop`
/// says so the finished frames are a prefix of the sequence and no frame is left half done.
/// Returns how many frames were finished (all `count` unless stopped). An exception escaping
/// `work` or `done` is rethrown here after every worker has stopped.
std::size_t runFramesInOrder(std::size_t count, int jobs, const FrameWork& work, const FrameDone& done,
                             const StopAsked& stop);

}  // namespace sequence
}  // namespace lidar_sgm
