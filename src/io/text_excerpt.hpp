#pragma once
/// @file text_excerpt.hpp  (private) Quoting file content in messages: a reader that was handed
/// the wrong file (a scan given as a calibration) must not print its raw bytes to the terminal.

#include <cstddef>
#include <string>
#include <string_view>

namespace lidar_sgm {
namespace io {
namespace detail {

/// Whether `bytes` (a file's first bytes, or all of it) look binary rather than text: a NUL, or
/// more than one in 20 bytes a control character other than tab, CR, LF and form feed.
bool looksBinary(std::string_view bytes);

/// At most `maxBytes` of `bytes`, printable: other bytes (control characters, bytes >= 0x7f) as
/// \xNN, and "..." when cut.
std::string printableExcerpt(std::string_view bytes, std::size_t maxBytes = 40);

}  // namespace detail
}  // namespace io
}  // namespace lidar_sgm
