#include "frame_folders.hpp"

#include <map>
#include <set>
#include <stdexcept>
#include <system_error>

#include "lidar_sgm/io/file_access.hpp"

namespace fs = std::filesystem;

namespace lidar_sgm {
namespace sequence {
namespace detail {
namespace {

bool isScan(const fs::path& path) {
  const std::string extension = io::lowerExtension(path.string());
  return extension == ".bin" || extension == ".pcd" || extension == ".ply";
}

/// `folder/stem.png` when it is a file, else "".
std::string imageFor(const fs::path& folder, const std::string& stem) {
  const fs::path image = folder / (stem + ".png");
  return isFile(image) ? image.string() : std::string();
}

/// The left images' stems of `folder` (PNG files).
std::set<std::string> imageStems(const fs::path& folder) {
  std::set<std::string> stems;
  std::error_code ec;
  for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) {
    std::error_code typeError;
    if (it->is_regular_file(typeError) && io::lowerExtension(it->path().string()) == ".png") {
      stems.insert(it->path().stem().string());
    }
  }
  return stems;
}

}  // namespace

std::vector<Frame> framesOf(const fs::path& scanFolder, const fs::path& leftFolder, const fs::path& rightFolder,
                            const std::string& namePrefix, CalibrationFormat format, MissingScans missing,
                            const std::function<std::string(const std::string&)>& calibOf) {
  std::map<std::string, fs::path> scans;  // by stem: name order
  for (const fs::directory_entry& entry : fs::directory_iterator(scanFolder)) {
    if (!entry.is_regular_file() || !isScan(entry.path())) continue;
    const std::string stem = entry.path().stem().string();
    if (!scans.emplace(stem, entry.path()).second) {
      throw std::invalid_argument("'" + scanFolder.string() + "' has two scans named '" + stem +
                                  "' (different extensions): which one is the frame?");
    }
  }
  if (missing == MissingScans::Reported) {
    const std::string extension = scans.empty() ? ".bin" : scans.begin()->second.extension().string();
    for (const std::string& stem : imageStems(leftFolder)) {
      if (scans.count(stem) == 0) scans.emplace(stem, scanFolder / (stem + extension));
    }
  }
  std::vector<Frame> frames;
  for (const auto& [stem, scan] : scans) {
    Frame frame;
    frame.name = namePrefix + stem;
    frame.scan = scan.string();
    frame.left = imageFor(leftFolder, stem);
    frame.right = frame.left.empty() ? std::string() : imageFor(rightFolder, stem);
    frame.calib = calibOf(stem);
    frame.calibFormat = format;
    frames.push_back(frame);
  }
  return frames;
}

bool isDirectory(const fs::path& path) {
  std::error_code ec;
  return fs::is_directory(path, ec);
}

bool isFile(const fs::path& path) {
  std::error_code ec;
  return fs::is_regular_file(path, ec);
}

}  // namespace detail
}  // namespace sequence
}  // namespace lidar_sgm
