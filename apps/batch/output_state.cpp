#include "batch/output_state.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
#include <regex>
#include <stdexcept>
#include <system_error>
#include <utility>

#include "common/output_paths.hpp"
#include "lidar_sgm/io/atomic_file.hpp"
#include "lidar_sgm/io/cloud_io.hpp"

namespace fs = std::filesystem;

namespace lidar_sgm {
namespace apps {
namespace {

/// A number's shortest exact text ("0.70" -> "0.7"); anything else as given.
std::string canonical(const std::string& value) {
  char* end = nullptr;
  errno = 0;
  const double number = std::strtod(value.c_str(), &end);
  if (value.empty() || end != value.c_str() + value.size() || errno != 0 || !std::isfinite(number)) return value;
  char text[64];
  std::snprintf(text, sizeof(text), "%.17g", number);
  // The shortest of %.15g..%.17g that reads back exactly.
  for (int digits = 15; digits <= 17; ++digits) {
    char shorter[64];
    std::snprintf(shorter, sizeof(shorter), "%.*g", digits, number);
    if (std::strtod(shorter, nullptr) == number) return shorter;
  }
  return text;
}

std::string readAll(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

}  // namespace

std::string cloudOptionsText(const Arguments& args, const std::set<std::string>& cloudOptionNames,
                             const std::string& extension) {
  std::string text = "-extension " + extension + "\n";
  for (const auto& [name, value] : args.values()) {  // std::map: sorted
    if (cloudOptionNames.count(name) > 0) text += "-" + name + " " + canonical(value) + "\n";
  }
  for (const std::string& name : args.flags()) {
    if (cloudOptionNames.count(name) > 0) text += "-" + name + "\n";
  }
  return text;
}

std::string cloudOptionsPath(const std::string& outDir) { return (fs::path(outDir) / "cloud_options.txt").string(); }

void checkAndRecordCloudOptions(const std::string& outDir, const std::string& options, bool overwrite) {
  const std::string path = cloudOptionsPath(outDir);
  if (fs::exists(path) && !overwrite) {
    const std::string recorded = readAll(path);
    if (recorded == options) return;
    auto oneLine = [](std::string s) {
      for (char& c : s) c = c == '\n' ? ' ' : c;
      while (!s.empty() && s.back() == ' ') s.pop_back();
      return s;
    };
    throw std::invalid_argument("the clouds in '" + outDir + "' were made with other options (" + oneLine(recorded) +
                                ") than this run's (" + oneLine(options) +
                                "): skipping their frames would mix both; use the same options, -overwrite to redo "
                                "every frame, or another -output_dir");
  }
  io::writeFileAtomically(path, options);
}

std::size_t removeStaleTemporaries(const std::vector<std::string>& outputs) {
  std::set<fs::path> targets;
  std::set<fs::path> folders;
  for (const std::string& output : outputs) {
    targets.insert(fs::path(output).lexically_normal());
    folders.insert(fs::path(output).lexically_normal().parent_path());
  }
  std::size_t removed = 0;
  for (const fs::path& folder : folders) {
    std::error_code ec;
    for (fs::directory_iterator it(folder.empty() ? fs::path(".") : folder, ec), end; !ec && it != end;
         it.increment(ec)) {
      const std::optional<io::TemporaryName> name = io::parseTemporaryName(it->path().filename().string());
      if (!name || targets.count(folder / name->output) == 0) continue;
      // A live writer's (another shard's, or a run of another folder's list that writes here).
      if (io::processAlive(name->pid)) continue;
      std::error_code removeError;
      if (fs::remove(it->path(), removeError)) ++removed;
    }
  }
  return removed;
}

std::string untrustedCloudReason(const std::string& path, const std::map<std::string, sequence::FrameRecord>& earlier,
                                 const std::string& frame) {
  std::error_code ec;
  const std::uintmax_t bytes = fs::file_size(path, ec);
  if (ec) return ec.message();
  const auto found = earlier.find(frame);
  if (found != earlier.end() && found->second.status == "ok" && found->second.bytes != bytes) {
    return "the manifest records " + std::to_string(found->second.bytes) + " bytes, the file has " +
           std::to_string(bytes);
  }
  try {
    io::checkCloudFile(path);
  } catch (const std::exception& e) {
    const std::string prefix = "cannot read cloud '" + path + "': ";
    const std::string what = e.what();
    return what.rfind(prefix, 0) == 0 ? what.substr(prefix.size()) : what;
  }
  return "";
}

std::map<std::string, sequence::FrameRecord> earlierFrameRecords(const std::string& outDir) {
  static const std::regex manifestName(R"(manifest(\.shard-[0-9]+-of-[0-9]+)?\.jsonl)");
  std::vector<std::pair<fs::file_time_type, fs::path>> manifests;
  std::error_code ec;
  for (fs::directory_iterator it(outDir, ec), end; !ec && it != end; it.increment(ec)) {
    if (!std::regex_match(it->path().filename().string(), manifestName)) continue;
    std::error_code timeError;
    const fs::file_time_type written = fs::last_write_time(it->path(), timeError);
    if (!timeError) manifests.emplace_back(written, it->path());
  }
  std::sort(manifests.begin(), manifests.end());  // oldest first: later records replace earlier ones
  std::map<std::string, sequence::FrameRecord> records;
  for (const auto& manifest : manifests) {
    std::ifstream in(manifest.second);
    for (std::string line; std::getline(in, line);) {
      const std::optional<sequence::FrameRecord> record = sequence::fromJsonLine(line);
      if (!record) continue;
      const bool carriesStatistics = record->points > 0 || record->ms.total() > 0.0;
      if (record->status == "ok" || (record->status == "skipped" && carriesStatistics)) {
        records[record->frame] = *record;
      }
    }
  }
  return records;
}

sequence::FrameRecord skippedFrameRecord(const std::string& frame, std::uintmax_t bytes,
                               const std::map<std::string, sequence::FrameRecord>& earlier) {
  sequence::FrameRecord record;
  const auto found = earlier.find(frame);
  if (found != earlier.end() && found->second.bytes == bytes) record = found->second;
  record.frame = frame;
  record.status = "skipped";
  record.bytes = bytes;
  record.error.clear();
  return record;
}

}  // namespace apps
}  // namespace lidar_sgm
