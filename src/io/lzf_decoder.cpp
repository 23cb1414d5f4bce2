#include "lzf_decoder.hpp"

namespace lidar_sgm {
namespace io {
namespace detail {

// The LZF stream (liblzf's lzf_d.c, which PCL copies): a control byte below 32 starts a literal
// run of control + 1 bytes; otherwise its top 3 bits are a length (7 = "read one more byte") and
// its low 5 bits with the next byte an offset back into the output.
bool lzfDecode(const std::uint8_t* in, std::size_t inSize, std::uint8_t* out, std::size_t outSize) {
  std::size_t ip = 0;
  std::size_t op = 0;
  while (ip < inSize) {
    const std::size_t control = in[ip++];
    if (control < 32) {
      const std::size_t length = control + 1;
      if (length > inSize - ip || length > outSize - op) return false;
      for (std::size_t k = 0; k < length; ++k) out[op++] = in[ip++];
      continue;
    }
    std::size_t length = control >> 5;
    if (length == 7) {
      if (ip >= inSize) return false;
      length += in[ip++];
    }
    if (ip >= inSize) return false;
    const std::size_t back = ((control & 0x1f) << 8) + in[ip++] + 1;
    length += 2;
    if (back > op || length > outSize - op) return false;
    // Byte by byte: the reference may overlap the bytes being written (a run).
    for (std::size_t k = 0; k < length; ++k, ++op) out[op] = out[op - back];
  }
  return op == outSize;
}

}  // namespace detail
}  // namespace io
}  // namespace lidar_sgm
