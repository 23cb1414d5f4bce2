#pragma once
// One run per output folder: two lidar_sgm_batch runs writing the same clouds would remove each
// other's temporaries as left by a dead run, do the work twice and interleave their manifests.
// A run holds a lock on a file in the folder (flock: the kernel releases it when the process
// ends, however it ends), so a second run on the same folder and shard is refused at once with
// the first one's pid; the shards of one folder (-shard K/N) still run side by side.

#include <string>

#include "lidar_sgm/sequence/frame_list.hpp"

namespace lidar_sgm {
namespace sequence {

class OutputFolderLock {
 public:
  /// Takes the lock of `outDir` (which exists) for `shard`: the folder's lock file
  /// ".lidar_sgm_batch.lock", exclusively for a run of the whole sequence, shared by the shards,
  /// and then each shard's own ".lidar_sgm_batch.shard-K-of-N.lock" exclusively. Throws
  /// std::runtime_error naming the folder and, where known, the pid of the run that holds it.
  OutputFolderLock(const std::string& outDir, const Shard& shard);
  ~OutputFolderLock();
  OutputFolderLock(const OutputFolderLock&) = delete;
  OutputFolderLock& operator=(const OutputFolderLock&) = delete;

 private:
  int folder_ = -1;
  int shard_ = -1;
  bool whole_ = false;  ///< folder_ is held exclusively (and holds this pid)
};

}  // namespace sequence
}  // namespace lidar_sgm
