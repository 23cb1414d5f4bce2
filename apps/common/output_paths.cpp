#include "common/output_paths.hpp"

#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
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

void writeFileAtomically(const std::string& path, const std::string& bytes) {
  namespace fs = std::filesystem;
  fs::path temporary(path);
  temporary.replace_filename("." + fs::path(path).stem().string() + ".tmp" + std::to_string(::getpid()) +
                             fs::path(path).extension().string());
  {
    std::ofstream out(temporary, std::ios::binary);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    out.close();
    if (!out) {
      std::error_code ignored;
      fs::remove(temporary, ignored);
      throw std::runtime_error("cannot write '" + path + "'");
    }
  }
  std::error_code ec;
  fs::rename(temporary, path, ec);
  if (ec) {
    std::error_code ignored;
    fs::remove(temporary, ignored);
    throw std::runtime_error("cannot write '" + path + "': " + ec.message());
  }
}

}  // namespace apps
}  // namespace lidar_sgm
