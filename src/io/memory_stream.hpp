#pragma once
/// @file memory_stream.hpp  A read-only, seekable std::istream over bytes the caller owns.
///
/// PCL's PCD header and ASCII-body readers take a std::istream; this lets them parse a buffer
/// in place (a std::istringstream would first copy the whole cloud). Seeking is needed: PCL's
/// readHeader() reports where the data starts with tellg().

#include <cstddef>
#include <ios>
#include <istream>
#include <streambuf>

namespace lidar_sgm {
namespace io {
namespace detail {

class MemoryBuffer : public std::streambuf {
 public:
  MemoryBuffer(const char* data, std::size_t size) {
    // The get area only: std::streambuf wants char*, but nothing is ever written through it.
    char* begin = const_cast<char*>(data);
    setg(begin, begin, begin + size);
  }

 protected:
  pos_type seekoff(off_type offset, std::ios_base::seekdir direction, std::ios_base::openmode which) override {
    if ((which & std::ios_base::in) == 0) return pos_type(off_type(-1));
    const off_type size = egptr() - eback();
    const off_type base = direction == std::ios_base::beg   ? 0
                          : direction == std::ios_base::cur ? gptr() - eback()
                                                            : size;
    const off_type target = base + offset;
    if (target < 0 || target > size) return pos_type(off_type(-1));
    setg(eback(), eback() + target, egptr());
    return pos_type(target);
  }

  pos_type seekpos(pos_type position, std::ios_base::openmode which) override {
    return seekoff(off_type(position), std::ios_base::beg, which);
  }
};

/// The buffer is a base (constructed first), not a member, so std::istream gets a live one.
class MemoryStream : private MemoryBuffer, public std::istream {
 public:
  MemoryStream(const char* data, std::size_t size) : MemoryBuffer(data, size), std::istream(this) {}
};

}  // namespace detail
}  // namespace io
}  // namespace lidar_sgm
