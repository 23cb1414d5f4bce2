#pragma once
// The batch's progress: frames done / total, frames/s and the time left. On a terminal one line
// redrawn in place (at most a few times a second); in a log (not a terminal) a plain line every
// N frames, so that a cluster job's log stays readable.

#include <cstddef>
#include <cstdio>
#include <string>

namespace lidar_sgm {
namespace apps {

/// Frames done so far, by outcome.
struct FrameCounts {
  std::size_t ok = 0;
  std::size_t skipped = 0;
  std::size_t failed = 0;
  std::size_t done() const { return ok + skipped + failed; }
};

/// "12 s", "3 min 20 s", "2 h 05 min".
std::string formatDuration(double seconds);

/// "20/100 frames (20 %), 1.80 frames/s, ETA 44 s". The rate counts densified frames only
/// (ok and failed), so that a resumed run's quick skips do not promise a short ETA.
std::string progressText(const FrameCounts& counts, std::size_t total, double seconds);

class Progress {
 public:
  /// Writes to `stream`; `terminal`: redraw one line in place; otherwise a line every `every`
  /// frames and at the last one.
  Progress(std::FILE* stream, bool terminal, std::size_t total, int every);

  /// After each frame.
  void update(const FrameCounts& counts, double seconds);
  /// Clears the terminal line (before other output goes to the terminal); no-op in a log.
  void clear();
  /// Ends the terminal line (before the summary).
  void finish();

 private:
  std::FILE* stream_;
  bool terminal_;
  std::size_t total_;
  std::size_t every_;
  double lastDrawn_ = -1.0;  ///< [s] when the terminal line was last drawn
  bool shown_ = false;
  FrameCounts last_;
  double lastSeconds_ = 0.0;
  void draw(const FrameCounts& counts, double seconds);
};

}  // namespace apps
}  // namespace lidar_sgm
