#pragma once
/// @file lzf_decoder.hpp  (private) A bounded LZF decoder for PCD "DATA binary_compressed".
///
/// PCL's own lzfDecompress trusts the sizes in the file and is where hostile PCD files crashed
/// it; this one checks every literal run and back reference against both buffers.

#include <cstddef>
#include <cstdint>

namespace lidar_sgm {
namespace io {
namespace detail {

/// Decodes the `inSize` LZF bytes at `in` into exactly `outSize` bytes at `out`. Returns false
/// (with `out` partly written) when the input is malformed: a run or reference that reads past
/// the input, writes past `outSize`, points before the output's start, or an output that does
/// not come out at exactly `outSize` bytes.
bool lzfDecode(const std::uint8_t* in, std::size_t inSize, std::uint8_t* out, std::size_t outSize);

/// The most an LZF block can expand: a 3-byte back reference stands for up to 264 bytes. A
/// declared uncompressed size above compressed x this is a lie, refused before allocating.
constexpr std::uint64_t kLzfMaxExpansion = 88;

}  // namespace detail
}  // namespace io
}  // namespace lidar_sgm
