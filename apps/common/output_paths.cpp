#include "common/output_paths.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <stdexcept>
#include <system_error>

namespace fs = std::filesystem;

namespace lidar_sgm {
namespace apps {

bool samePath(const std::string& a, const std::string& b) {
  std::error_code ec;
  if (fs::exists(a, ec) && fs::exists(b, ec)) return fs::equivalent(a, b, ec);
  return fs::weakly_canonical(a, ec) == fs::weakly_canonical(b, ec);
}

std::string lowerExtension(const std::string& path) {
  std::string extension = fs::path(path).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return extension;
}

void requireOutput(const std::string& path, const std::vector<std::string>& extensions,
                   const std::vector<std::string>& inputs) {
  if (std::find(extensions.begin(), extensions.end(), lowerExtension(path)) == extensions.end()) {
    std::string accepted;
    for (const std::string& e : extensions) accepted += (accepted.empty() ? "" : " or ") + e;
    throw std::invalid_argument("output '" + path + "' must be a " + accepted + " file");
  }
  for (const std::string& input : inputs) {
    if (!input.empty() && samePath(path, input)) {
      throw std::invalid_argument("output '" + path + "' is the input '" + input + "'; refusing to overwrite an input");
    }
  }
}

}  // namespace apps
}  // namespace lidar_sgm
