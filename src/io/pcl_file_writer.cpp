#include "pcl_file_writer.hpp"

#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>

namespace lidar_sgm {
namespace io {
namespace detail {
namespace {

[[noreturn]] void failMemory(const std::string& what) {
  throw std::runtime_error("the memory file: " + what + ": " + std::strerror(errno));
}

/// The memory file, closed (and freed) on every path out.
class MemoryFile {
 public:
  MemoryFile() : descriptor_(::memfd_create("lidar_sgm_cloud", MFD_CLOEXEC)) {
    if (descriptor_ < 0) failMemory("cannot create it");
  }
  ~MemoryFile() { ::close(descriptor_); }
  MemoryFile(const MemoryFile&) = delete;
  MemoryFile& operator=(const MemoryFile&) = delete;

  /// A name by which other code (PCL's writers) opens this very file.
  std::string name() const { return "/proc/self/fd/" + std::to_string(descriptor_); }
  int descriptor() const { return descriptor_; }

 private:
  int descriptor_;
};

/// The memory file's bytes, mapped read-only (nothing else holds the file: it cannot shrink).
class MappedBytes {
 public:
  explicit MappedBytes(const MemoryFile& file) {
    struct stat status {};
    if (::fstat(file.descriptor(), &status) != 0) failMemory("cannot read its size");
    size_ = static_cast<std::size_t>(status.st_size);
    if (size_ == 0) return;
    void* mapped = ::mmap(nullptr, size_, PROT_READ, MAP_PRIVATE, file.descriptor(), 0);
    if (mapped == MAP_FAILED) failMemory("cannot map it");
    bytes_ = static_cast<const std::uint8_t*>(mapped);
  }
  ~MappedBytes() {
    if (bytes_ != nullptr) ::munmap(const_cast<std::uint8_t*>(bytes_), size_);
  }
  MappedBytes(const MappedBytes&) = delete;
  MappedBytes& operator=(const MappedBytes&) = delete;

  const std::uint8_t* bytes() const { return bytes_; }
  std::size_t size() const { return size_; }

 private:
  const std::uint8_t* bytes_ = nullptr;
  std::size_t size_ = 0;
};

}  // namespace

void writeThroughPcl(AtomicFile& out, const std::function<int(const std::string& file)>& write,
                     const std::function<void(const std::uint8_t* bytes, std::size_t size)>& verify) {
  const MemoryFile memory;
  if (write(memory.name()) != 0) throw std::runtime_error("PCL's writer failed");
  const MappedBytes written(memory);
  verify(written.bytes(), written.size());
  out.write(written.bytes(), written.size());
}

}  // namespace detail
}  // namespace io
}  // namespace lidar_sgm
