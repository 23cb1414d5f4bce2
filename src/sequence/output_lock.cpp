#include "lidar_sgm/sequence/output_lock.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <stdexcept>

#include "lidar_sgm/io/atomic_file.hpp"

namespace fs = std::filesystem;

namespace lidar_sgm {
namespace sequence {
namespace {

int openLockFile(const std::string& path) {
  const int descriptor = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0666);
  if (descriptor < 0) {
    throw std::runtime_error("cannot lock the output folder: cannot open '" + path + "': " + std::strerror(errno));
  }
  return descriptor;
}

/// The pid a live holder wrote into the lock file ("" when none: the shards share it, and a run
/// killed before it could clear its pid left a dead one).
std::string holderOf(int descriptor) {
  char text[32] = {};
  const ssize_t got = ::pread(descriptor, text, sizeof(text) - 1, 0);
  if (got <= 0) return "";
  const long pid = std::strtol(text, nullptr, 10);
  return io::processAlive(pid) ? std::to_string(pid) : "";
}

/// Writes this process's pid into the lock file it holds exclusively, for the next one's message.
void recordHolder(int descriptor) {
  const std::string pid = std::to_string(::getpid()) + "\n";
  if (::ftruncate(descriptor, 0) == 0) {
    // The pid only serves messages: a lock file that cannot hold it still locks.
    [[maybe_unused]] const ssize_t written = ::pwrite(descriptor, pid.data(), pid.size(), 0);
  }
}

/// Clears the pid when the run ends: the pid of a run that ended says nothing.
void clearHolder(int descriptor) {
  if (::ftruncate(descriptor, 0) != 0) {
    // Only messages depend on it, and holderOf() checks that the pid lives.
  }
}

/// flock without waiting; false when another process holds a conflicting lock.
bool tryLock(int descriptor, int operation, const std::string& path) {
  while (::flock(descriptor, operation | LOCK_NB) != 0) {
    if (errno == EINTR) continue;
    if (errno == EWOULDBLOCK) return false;
    throw std::runtime_error("cannot lock the output folder: '" + path + "': " + std::strerror(errno));
  }
  return true;
}

}  // namespace

OutputFolderLock::OutputFolderLock(const std::string& outDir, const Shard& shard) {
  const std::string folderPath = (fs::path(outDir) / ".lidar_sgm_batch.lock").string();
  const bool whole = shard.count == 1;
  folder_ = openLockFile(folderPath);
  if (!tryLock(folder_, whole ? LOCK_EX : LOCK_SH, folderPath)) {
    const std::string holder = holderOf(folder_);
    ::close(folder_);
    throw std::runtime_error(
        "another lidar_sgm_batch run is writing '" + outDir + "' (" +
        (holder.empty() ? std::string("shards of a run") : "pid " + holder + ", the whole sequence") +
        "): two runs on one folder would undo each other's work; wait for it to end, or use another -output_dir");
  }
  if (whole) {
    whole_ = true;
    recordHolder(folder_);
    return;
  }
  const std::string name =
      ".lidar_sgm_batch.shard-" + std::to_string(shard.index) + "-of-" + std::to_string(shard.count) + ".lock";
  const std::string shardPath = (fs::path(outDir) / name).string();
  shard_ = openLockFile(shardPath);
  if (!tryLock(shard_, LOCK_EX, shardPath)) {
    const std::string holder = holderOf(shard_);
    ::close(shard_);
    ::close(folder_);
    throw std::runtime_error("another lidar_sgm_batch run (pid " + (holder.empty() ? "unknown" : holder) +
                             ") is writing shard " + std::to_string(shard.index) + "/" + std::to_string(shard.count) +
                             " of '" + outDir + "': wait for it to end, or use another -output_dir");
  }
  recordHolder(shard_);
}

OutputFolderLock::~OutputFolderLock() {
  // Closing releases the locks; the files stay (removing a lock file races with its next taker).
  if (shard_ >= 0) {
    clearHolder(shard_);
    ::close(shard_);
  }
  if (folder_ >= 0) {
    if (whole_) clearHolder(folder_);
    ::close(folder_);
  }
}

}  // namespace sequence
}  // namespace lidar_sgm
