#pragma once
// What an output folder holds from earlier runs: the options its clouds were made with (so that a
// re-run never skips frames made with other options and mixes two methods in one sequence), the
// hidden temporary files a killed run (kill -9, a node lost) may have left, and the manifests'
// records of the frames made.

#include <cstdint>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "lidar_sgm/sequence/manifest.hpp"
#include "common/arguments.hpp"

namespace lidar_sgm {
namespace apps {

/// The options that decide a cloud's bytes, one "-name value" (or "-name") per line, sorted;
/// numbers written canonically so that "-alpha 0.70" equals "-alpha 0.7". `cloudOptionNames`
/// are the options that count (the method's and the output's: not -threads, -jobs, -shard, ...);
/// `extension` is the clouds' file type.
std::string cloudOptionsText(const Arguments& args, const std::set<std::string>& cloudOptionNames,
                             const std::string& extension);

/// The file in `outDir` that records the cloud options.
std::string cloudOptionsPath(const std::string& outDir);

/// Checks `outDir`'s recorded cloud options against `options`: none recorded (a new folder) or
/// the same -> records them (atomically; shards racing write the same bytes). Different ->
/// std::invalid_argument naming both, unless `overwrite` (every frame is redone: the new
/// options are recorded).
void checkAndRecordCloudOptions(const std::string& outDir, const std::string& options, bool overwrite);

/// Removes the hidden temporary files (".<stem>.tmp<pid>.<ext>") that an interrupted run, no
/// longer alive, left beside the clouds `outputs`; a live process's are left alone. Returns how
/// many were removed.
std::size_t removeStaleTemporaries(const std::vector<std::string>& outputs);

/// Why the existing cloud `path` of frame `frame` cannot be trusted as done, or "" when it can:
/// its size differs from what `earlier` (the manifests) records of it, or it is not whole
/// (io::checkCloudFile: a cloud cut short by a full disk, or written by other means and broken).
std::string untrustedCloudReason(const std::string& path, const std::map<std::string, sequence::FrameRecord>& earlier,
                                 const std::string& frame);

/// What the manifests in `outDir` (manifest.jsonl and the shards' manifest.shard-K-of-N.jsonl)
/// say of the frames whose clouds earlier runs made, by frame name: their "ok" records, and
/// "skipped" ones that carry such a record's statistics. Where several manifests have a frame,
/// the last written (file time) wins. Read before this run's manifest replaces its own;
/// unreadable files and lines are passed over (they are statistics, not state).
std::map<std::string, sequence::FrameRecord> earlierFrameRecords(const std::string& outDir);

/// The record of frame `frame`, skipped because its cloud of `bytes` exists: status "skipped",
/// with the points and timings of the run that made the cloud when `earlier` has a record of it
/// of the same size (else 0: a cloud made or replaced by other means has no statistics here).
sequence::FrameRecord skippedFrameRecord(const std::string& frame, std::uintmax_t bytes,
                               const std::map<std::string, sequence::FrameRecord>& earlier);

}  // namespace apps
}  // namespace lidar_sgm
