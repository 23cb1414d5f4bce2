#pragma once
// A file size limit (RLIMIT_FSIZE) for one scope: every write past `bytes` fails with EFBIG, as
// on a full disk a write fails with ENOSPC, in any file system and without privileges. SIGXFSZ,
// which would kill the process, is ignored meanwhile.

#include <sys/resource.h>

#include <csignal>
#include <cstdint>

namespace lidar_sgm {
namespace test {

class FileSizeLimit {
 public:
  explicit FileSizeLimit(std::uint64_t bytes) {
    ::getrlimit(RLIMIT_FSIZE, &saved_);
    previousHandler_ = std::signal(SIGXFSZ, SIG_IGN);
    struct rlimit limit = saved_;
    limit.rlim_cur = static_cast<rlim_t>(bytes);
    ::setrlimit(RLIMIT_FSIZE, &limit);
  }
  ~FileSizeLimit() {
    ::setrlimit(RLIMIT_FSIZE, &saved_);
    std::signal(SIGXFSZ, previousHandler_);
  }
  FileSizeLimit(const FileSizeLimit&) = delete;
  FileSizeLimit& operator=(const FileSizeLimit&) = delete;

 private:
  struct rlimit saved_ {};
  void (*previousHandler_)(int) = SIG_DFL;
};

}  // namespace test
}  // namespace lidar_sgm
