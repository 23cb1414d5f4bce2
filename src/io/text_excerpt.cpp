#include "text_excerpt.hpp"

#include <cstdio>

namespace lidar_sgm {
namespace io {
namespace detail {
namespace {

bool isTextControl(unsigned char c) { return c == '\t' || c == '\r' || c == '\n' || c == '\f'; }

}  // namespace

bool looksBinary(std::string_view bytes) {
  std::size_t controls = 0;
  for (const char byte : bytes) {
    const auto c = static_cast<unsigned char>(byte);
    if (c == 0) return true;
    if ((c < 0x20 || c == 0x7f) && !isTextControl(c)) ++controls;
  }
  return controls * 20 > bytes.size();
}

std::string printableExcerpt(std::string_view bytes, std::size_t maxBytes) {
  std::string out;
  const std::size_t shown = bytes.size() < maxBytes ? bytes.size() : maxBytes;
  for (std::size_t i = 0; i < shown; ++i) {
    const auto c = static_cast<unsigned char>(bytes[i]);
    // UTF-8 is escaped too: a cut multi-byte sequence would print as garbage.
    if (c >= 0x20 && c < 0x7f && c != '\\') {
      out += static_cast<char>(c);
    } else {
      char escaped[5];
      std::snprintf(escaped, sizeof escaped, "\\x%02x", c);
      out += escaped;
    }
  }
  if (shown < bytes.size()) out += "...";
  return out;
}

}  // namespace detail
}  // namespace io
}  // namespace lidar_sgm
