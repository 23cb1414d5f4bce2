#pragma once
/// @file atomic_file.hpp  Every output file is written whole or not at all: written to a hidden
/// temporary beside it, every write checked, synced to the disk and its size checked, and only
/// then renamed over the output. A full disk, a file size limit, a read-only or immutable folder
/// never leaves a truncated file under the output's name, and never replaces an existing one.

#include <cstddef>
#include <optional>
#include <string>

namespace lidar_sgm {
namespace io {

/// A file being written: created as a hidden temporary ("dir/.stem.tmpPID.ext", temporaryPathFor)
/// and renamed over its path by commit(). Destroyed without commit(), it removes the temporary.
/// Every failure throws std::runtime_error "cannot write 'PATH': REASON", REASON the system's
/// (strerror: "No space left on device", "Operation not permitted", "Read-only file system", ...).
class AtomicFile {
 public:
  explicit AtomicFile(std::string path);
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  /// Appends `size` bytes: write() until all are written (a short write is resumed, an error
  /// is thrown, never ignored).
  void write(const void* data, std::size_t size);
  void write(const std::string& bytes) { write(bytes.data(), bytes.size()); }

  /// Makes the file the output: fdatasync (a full disk may only show there), its size checked
  /// against the bytes written, close checked, then renamed over the path.
  void commit();

  const std::string& path() const { return path_; }
  const std::string& temporaryPath() const { return temporary_; }
  std::size_t bytesWritten() const { return written_; }

 private:
  [[noreturn]] void fail(const std::string& reason);

  std::string path_;
  std::string temporary_;
  int descriptor_ = -1;
  std::size_t written_ = 0;
};

/// Writes `size` bytes at `data` (or `bytes`) to `path` through an AtomicFile.
void writeFileAtomically(const std::string& path, const void* data, std::size_t size);
void writeFileAtomically(const std::string& path, const std::string& bytes);

/// The hidden temporary that process `pid` writes `path` through: "dir/.stem.tmpPID.ext", in the
/// same folder (so that the rename is atomic) and with the same extension (for writers that
/// choose the format by it). Every writer of the library and the tools names them so.
std::string temporaryPathFor(const std::string& path, long pid);
/// The same for this process.
std::string temporaryPathFor(const std::string& path);

/// What a hidden temporary's file name says: the output's file name and its writer's pid.
struct TemporaryName {
  std::string output;  ///< "stem.ext"
  long pid = 0;
};
/// Reads a file name as temporaryPathFor() makes them (".stem.tmpPID.ext", or ".stem.tmpPID-N.ext"
/// when that name was taken); std::nullopt for any other name.
std::optional<TemporaryName> parseTemporaryName(const std::string& fileName);

/// Whether process `pid` is alive (also when it belongs to another user).
bool processAlive(long pid);

/// Removes the temporary if it exists; never throws (for error paths).
void discardTemporary(const std::string& temporary) noexcept;

}  // namespace io
}  // namespace lidar_sgm
