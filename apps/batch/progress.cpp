#include "batch/progress.hpp"

namespace lidar_sgm {
namespace apps {
namespace {
constexpr double kRedrawSeconds = 0.25;  // a terminal line redrawn faster is unreadable
}

std::string formatDuration(double seconds) {
  const long s = static_cast<long>(seconds + 0.5);
  char text[64];
  if (s < 60) {
    std::snprintf(text, sizeof(text), "%ld s", s);
  } else if (s < 3600) {
    std::snprintf(text, sizeof(text), "%ld min %02ld s", s / 60, s % 60);
  } else {
    std::snprintf(text, sizeof(text), "%ld h %02ld min", s / 3600, (s % 3600) / 60);
  }
  return text;
}

std::string progressText(const FrameCounts& counts, std::size_t total, double seconds) {
  const std::size_t worked = counts.ok + counts.failed;
  const double rate = seconds > 0.0 ? static_cast<double>(worked) / seconds : 0.0;
  const std::size_t left = total - counts.done();
  const std::string eta =
      left == 0 ? "0 s" : rate > 0.0 ? formatDuration(static_cast<double>(left) / rate) : std::string("unknown");
  char text[160];
  std::snprintf(text, sizeof(text), "%zu/%zu frames (%.0f %%), %.2f frames/s, ETA %s", counts.done(), total,
                total == 0 ? 100.0 : 100.0 * static_cast<double>(counts.done()) / static_cast<double>(total), rate,
                eta.c_str());
  return text;
}

Progress::Progress(std::FILE* stream, bool terminal, std::size_t total, int every)
    : stream_(stream), terminal_(terminal), total_(total), every_(every < 1 ? 1 : static_cast<std::size_t>(every)) {}

void Progress::draw(const FrameCounts& counts, double seconds) {
  // "\r\033[K": back to the line's start and clear it, so a shorter line leaves no tail.
  std::fprintf(stream_, "\r\033[KProgress: %s", progressText(counts, total_, seconds).c_str());
  std::fflush(stream_);
  shown_ = true;
  lastDrawn_ = seconds;
}

void Progress::update(const FrameCounts& counts, double seconds) {
  last_ = counts;
  lastSeconds_ = seconds;
  if (terminal_) {
    if (lastDrawn_ < 0.0 || seconds - lastDrawn_ >= kRedrawSeconds || counts.done() == total_) draw(counts, seconds);
    return;
  }
  if (counts.done() % every_ == 0 || counts.done() == total_) {
    std::fprintf(stream_, "Progress: %s\n", progressText(counts, total_, seconds).c_str());
    std::fflush(stream_);
  }
}

void Progress::clear() {
  if (!terminal_ || !shown_) return;
  std::fprintf(stream_, "\r\033[K");
  std::fflush(stream_);
  shown_ = false;
  lastDrawn_ = -1.0;  // redrawn at the next update
}

void Progress::finish() {
  if (!terminal_) return;
  draw(last_, lastSeconds_);
  std::fprintf(stream_, "\n");
  std::fflush(stream_);
  shown_ = false;
}

}  // namespace apps
}  // namespace lidar_sgm
