#pragma once
// The frames of one scan folder with its image folders: what every directory layout shares
// (frame_list.cpp and kitti2015_layout.cpp), so each layout only says where its folders are.

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "lidar_sgm/sequence/frame_list.hpp"

namespace lidar_sgm {
namespace sequence {
namespace detail {

/// Whether a left image without a scan is a frame whose scan is missing.
enum class MissingScans { Ignored, Reported };

/// One frame per scan (.bin, .pcd, .ply) in `scanFolder`, in name order; its images are the .png
/// of its stem in `leftFolder`/`rightFolder` when present; `calibOf` gives a frame's calibration
/// file from its stem. With MissingScans::Reported (a sequence, where every image has its scan) a
/// left image without a scan is a frame too, whose scan path names the missing file: it fails,
/// with that cause, instead of vanishing from the sequence. Throws std::invalid_argument for two
/// scans of one stem.
std::vector<Frame> framesOf(const std::filesystem::path& scanFolder, const std::filesystem::path& leftFolder,
                            const std::filesystem::path& rightFolder, const std::string& namePrefix,
                            CalibrationFormat format, MissingScans missing,
                            const std::function<std::string(const std::string&)>& calibOf);

/// Whether `path` is a folder (false, not an exception, when it cannot be read).
bool isDirectory(const std::filesystem::path& path);
/// Whether `path` is a regular file (false, not an exception, when it cannot be read).
bool isFile(const std::filesystem::path& path);

}  // namespace detail
}  // namespace sequence
}  // namespace lidar_sgm
