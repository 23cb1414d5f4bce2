#pragma once
// What an output folder holds from earlier runs: the options its clouds were made with (so that a
// re-run never skips frames made with other options and mixes two methods in one sequence), and
// the hidden temporary files a killed run (kill -9, a node lost) may have left.

#include <set>
#include <string>
#include <vector>

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

/// Removes the hidden temporary files (".<stem>.tmp<pid>.<ext>") that an interrupted run left
/// beside the clouds `outputs` (this shard's frames: no other process writes them, so no other
/// process's file is touched). Returns how many were removed.
std::size_t removeStaleTemporaries(const std::vector<std::string>& outputs);

}  // namespace apps
}  // namespace lidar_sgm
