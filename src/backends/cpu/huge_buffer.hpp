#pragma once
// A large, uninitialised buffer on 2 MiB transparent huge pages (allocateHugePages,
// lidar_sgm/core/huge_page_allocator.hpp says why): the cost volume, written once per frame before
// it is read, so neither std::vector's zeroing nor a page fault per 4 KiB is wanted.

#include <algorithm>
#include <cstddef>
#include <cstdlib>
#include <memory>

#include "lidar_sgm/core/huge_page_allocator.hpp"

namespace lidar_sgm {
namespace cpu {

template <typename T>
class HugeBuffer {
 public:
  T* data() { return data_.get(); }
  const T* data() const { return data_.get(); }
  std::size_t size() const { return size_; }

  /// Holds at least n elements afterwards; grows only (the contents are then undefined).
  void reserve(std::size_t n) {
    if (n <= size_) return;
    const std::size_t bytes = hugePageBytes(n * sizeof(T));
    data_.reset(static_cast<T*>(allocateHugePages(bytes)));
    data_.get_deleter().bytes = bytes;
    size_ = bytes / sizeof(T);
  }

 private:
  struct Free {
    std::size_t bytes = 0;
    void operator()(T* p) const { freeHugePages(p, bytes); }
  };
  std::unique_ptr<T, Free> data_;
  std::size_t size_ = 0;
};

}  // namespace cpu
}  // namespace lidar_sgm
