#include "batch/manifest.hpp"

#include <cerrno>
#include <cstring>
#include <stdexcept>

namespace lidar_sgm {
namespace apps {

std::string jsonEscape(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    switch (c) {
      case '"': out += "\\\""; break;
      case '\\': out += "\\\\"; break;
      case '\n': out += "\\n"; break;
      case '\r': out += "\\r"; break;
      case '\t': out += "\\t"; break;
      default:
        if (static_cast<unsigned char>(c) < 0x20) {
          char escaped[8];
          std::snprintf(escaped, sizeof(escaped), "\\u%04x", static_cast<unsigned>(static_cast<unsigned char>(c)));
          out += escaped;
        } else {
          out += c;
        }
    }
  }
  return out;
}

std::string toJsonLine(const FrameRecord& r) {
  char timings[256];
  std::snprintf(timings, sizeof(timings),
                "\"load_ms\":%.1f,\"project_ms\":%.1f,\"match_ms\":%.1f,\"reproject_ms\":%.1f,\"save_ms\":%.1f,"
                "\"total_ms\":%.1f",
                r.ms.load, r.ms.project, r.ms.match, r.ms.reproject, r.ms.save, r.ms.total());
  return "{\"frame\":\"" + jsonEscape(r.frame) + "\",\"status\":\"" + jsonEscape(r.status) +
         "\",\"points\":" + std::to_string(r.points) + ",\"bytes\":" + std::to_string(r.bytes) + "," + timings + ",\"error\":\"" + jsonEscape(r.error) + "\"}";
}

Manifest::Manifest(const std::string& path) : path_(path), file_(std::fopen(path.c_str(), "w")) {
  if (!file_) throw std::runtime_error("cannot create the manifest '" + path + "': " + std::strerror(errno));
}

Manifest::~Manifest() {
  if (file_) std::fclose(file_);
}

void Manifest::append(const FrameRecord& record) {
  const std::string line = toJsonLine(record) + "\n";
  if (std::fwrite(line.data(), 1, line.size(), file_) != line.size() || std::fflush(file_) != 0) {
    throw std::runtime_error("cannot write the manifest '" + path_ + "': " + std::strerror(errno));
  }
}

}  // namespace apps
}  // namespace lidar_sgm
