#pragma once
// The batch's manifest: one JSON line per frame, appended as the frame ends, so that a run that
// is stopped still says what it did.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

namespace lidar_sgm {
namespace sequence {

/// Where a frame's time went [ms]; 0 for a skipped or failed frame's untimed stages.
struct FrameTimings {
  double load = 0;       ///< scan, calibration, images
  double project = 0;    ///< the Densifier's stages (DensificationTimings)
  double match = 0;
  double reproject = 0;
  double save = 0;       ///< -voxel down-sampling and the cloud written (atomically)
  double total() const { return load + project + match + reproject + save; }
};

/// One frame's line.
struct FrameRecord {
  std::string frame;
  std::string status;  ///< "ok", "skipped" (its output was already complete) or "failed"
  std::size_t points = 0;
  std::uintmax_t bytes = 0;  ///< the cloud file's size (also for a skipped frame's existing file)
  FrameTimings ms;
  std::string error;   ///< why it failed; empty otherwise
  std::string redone;  ///< why an earlier run's cloud of the frame was not trusted (so it was made
                       ///< again); empty otherwise, and then not written
};

/// `text` as a JSON string's contents: quotes, backslashes and control characters escaped.
std::string jsonEscape(const std::string& text);

/// The record as one JSON object on one line (no newline):
/// {"frame":..,"status":..,"points":..,"bytes":..,"load_ms":..,"project_ms":..,"match_ms":..,
///  "reproject_ms":..,"save_ms":..,"total_ms":..,"error":..[,"redone":..]}
std::string toJsonLine(const FrameRecord& record);

/// The record of a line toJsonLine() wrote (total_ms, the sum, is not kept); std::nullopt for
/// any other line (another program's, a line cut short by a killed run).
std::optional<FrameRecord> fromJsonLine(const std::string& line);

/// A manifest file, created empty (a re-run writes its own, listing the frames it skipped).
class Manifest {
 public:
  /// Throws std::runtime_error naming `path` when it cannot be created.
  explicit Manifest(const std::string& path);
  ~Manifest();
  Manifest(const Manifest&) = delete;
  Manifest& operator=(const Manifest&) = delete;

  /// Appends the record's line with one write(). Throws std::runtime_error on failure (a line
  /// cut short stays as it is: fromJsonLine() passes it over).
  void append(const FrameRecord& record);
  const std::string& path() const { return path_; }

 private:
  std::string path_;
  int descriptor_ = -1;
};

}  // namespace sequence
}  // namespace lidar_sgm
