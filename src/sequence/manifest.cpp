#include "lidar_sgm/sequence/manifest.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <map>
#include <stdexcept>
#include <utility>

namespace lidar_sgm {
namespace sequence {

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
         "\",\"points\":" + std::to_string(r.points) + ",\"bytes\":" + std::to_string(r.bytes) + "," + timings + ",\"error\":\"" + jsonEscape(r.error) + "\"" +
         (r.redone.empty() ? "" : ",\"redone\":\"" + jsonEscape(r.redone) + "\"") + "}";
}

namespace {

/// The flat JSON object toJsonLine() writes: string and number values by key; false when `line`
/// is not one.
bool parseFlatObject(const std::string& line, std::map<std::string, std::string>& strings,
                     std::map<std::string, double>& numbers) {
  std::size_t at = 0;
  const auto skipSpace = [&] {
    while (at < line.size() && (line[at] == ' ' || line[at] == '\t' || line[at] == '\r')) ++at;
  };
  const auto readString = [&](std::string& out) {
    if (at >= line.size() || line[at] != '"') return false;
    for (++at; at < line.size(); ++at) {
      const char c = line[at];
      if (c == '"') {
        ++at;
        return true;
      }
      if (c != '\\') {
        out += c;
        continue;
      }
      if (++at >= line.size()) return false;
      switch (line[at]) {
        case '"': out += '"'; break;
        case '\\': out += '\\'; break;
        case '/': out += '/'; break;
        case 'n': out += '\n'; break;
        case 'r': out += '\r'; break;
        case 't': out += '\t'; break;
        case 'u': {  // jsonEscape writes \u00XX for the other control characters only
          if (at + 4 >= line.size()) return false;
          char* end = nullptr;
          const std::string hex = line.substr(at + 1, 4);
          const long code = std::strtol(hex.c_str(), &end, 16);
          if (end != hex.c_str() + 4 || code > 0x7f) return false;
          out += static_cast<char>(code);
          at += 4;
          break;
        }
        default: return false;
      }
    }
    return false;
  };
  skipSpace();
  if (at >= line.size() || line[at++] != '{') return false;
  for (;;) {
    skipSpace();
    std::string key;
    if (!readString(key)) return false;
    skipSpace();
    if (at >= line.size() || line[at++] != ':') return false;
    skipSpace();
    if (at < line.size() && line[at] == '"') {
      std::string value;
      if (!readString(value)) return false;
      strings[key] = value;
    } else {
      const char* begin = line.c_str() + at;
      char* end = nullptr;
      const double value = std::strtod(begin, &end);
      if (end == begin || !std::isfinite(value)) return false;
      numbers[key] = value;
      at += static_cast<std::size_t>(end - begin);
    }
    skipSpace();
    if (at >= line.size()) return false;
    const char next = line[at++];
    if (next == '}') break;
    if (next != ',') return false;
  }
  skipSpace();
  return at == line.size();
}

}  // namespace

std::optional<FrameRecord> fromJsonLine(const std::string& line) {
  std::map<std::string, std::string> strings;
  std::map<std::string, double> numbers;
  if (!parseFlatObject(line, strings, numbers)) return std::nullopt;
  FrameRecord record;
  for (const auto& [key, value] : {std::pair<const char*, std::string*>{"frame", &record.frame},
                                   {"status", &record.status},
                                   {"error", &record.error}}) {
    const auto found = strings.find(key);
    if (found == strings.end()) return std::nullopt;
    *value = found->second;
  }
  for (const auto& [key, value] : {std::pair<const char*, double*>{"load_ms", &record.ms.load},
                                   {"project_ms", &record.ms.project},
                                   {"match_ms", &record.ms.match},
                                   {"reproject_ms", &record.ms.reproject},
                                   {"save_ms", &record.ms.save}}) {
    const auto found = numbers.find(key);
    if (found == numbers.end()) return std::nullopt;
    *value = found->second;
  }
  const auto redone = strings.find("redone");  // only where a frame was redone
  if (redone != strings.end()) record.redone = redone->second;
  const auto points = numbers.find("points");
  const auto bytes = numbers.find("bytes");
  if (points == numbers.end() || bytes == numbers.end() || points->second < 0 || bytes->second < 0) return std::nullopt;
  record.points = static_cast<std::size_t>(points->second);
  record.bytes = static_cast<std::uintmax_t>(bytes->second);
  return record;
}

Manifest::Manifest(const std::string& path)
    : path_(path), descriptor_(::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_APPEND | O_CLOEXEC, 0666)) {
  if (descriptor_ < 0) throw std::runtime_error("cannot create the manifest '" + path + "': " + std::strerror(errno));
}

Manifest::~Manifest() {
  if (descriptor_ >= 0) ::close(descriptor_);
}

void Manifest::append(const FrameRecord& record) {
  // One write() per line, appended (O_APPEND): a line is whole or absent, never interleaved.
  const std::string line = toJsonLine(record) + "\n";
  for (;;) {
    const ssize_t written = ::write(descriptor_, line.data(), line.size());
    if (written == static_cast<ssize_t>(line.size())) return;
    if (written < 0 && errno == EINTR) continue;
    const std::string reason = written < 0 ? std::strerror(errno) : "the line was cut short (a full disk?)";
    throw std::runtime_error("cannot write the manifest '" + path_ + "': " + reason);
  }
}

}  // namespace sequence
}  // namespace lidar_sgm
