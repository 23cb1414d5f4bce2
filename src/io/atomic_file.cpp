#include "lidar_sgm/io/atomic_file.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <regex>
#include <stdexcept>
#include <system_error>
#include <utility>

namespace fs = std::filesystem;

namespace lidar_sgm {
namespace io {
namespace {

// Another temporary of the same output by this pid exists only when a thread of this process
// writes the same path, or a dead process with this pid left it: then ".stem.tmpPID-N.ext".
constexpr int kMaxNameAttempts = 100;

std::string systemReason(int error) { return std::strerror(error); }

/// "dir/.stem.tmpPID[-N].ext"
std::string temporaryName(const std::string& path, long pid, int attempt) {
  const fs::path target(path);
  fs::path temporary(target);
  std::string name = "." + target.stem().string() + ".tmp" + std::to_string(pid);
  if (attempt > 0) name += "-" + std::to_string(attempt);
  temporary.replace_filename(name + target.extension().string());
  return temporary.string();
}

/// Why a file cannot be created in `path`'s folder, in words: a missing folder is named.
std::string createFailure(const std::string& path, int error) {
  if (error == ENOENT) {
    const fs::path folder = fs::path(path).has_parent_path() ? fs::path(path).parent_path() : fs::path(".");
    return "the folder '" + folder.string() + "' does not exist";
  }
  return systemReason(error);
}

}  // namespace

AtomicFile::AtomicFile(std::string path) : path_(std::move(path)) {
  const long pid = static_cast<long>(::getpid());
  for (int attempt = 0; attempt < kMaxNameAttempts; ++attempt) {
    temporary_ = temporaryName(path_, pid, attempt);
    // O_EXCL: never write into a file someone else has open, nor through a planted symlink.
    descriptor_ = ::open(temporary_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (descriptor_ >= 0) return;
    if (errno != EEXIST) break;
  }
  const int error = errno;
  temporary_.clear();  // nothing of ours to remove
  throw std::runtime_error("cannot write '" + path_ + "': " + createFailure(path_, error));
}

AtomicFile::~AtomicFile() {
  if (descriptor_ >= 0) ::close(descriptor_);
  if (!temporary_.empty()) discardTemporary(temporary_);
}

void AtomicFile::fail(const std::string& reason) {
  if (descriptor_ >= 0) ::close(descriptor_);
  descriptor_ = -1;
  discardTemporary(temporary_);
  temporary_.clear();
  throw std::runtime_error("cannot write '" + path_ + "': " + reason);
}

void AtomicFile::write(const void* data, std::size_t size) {
  if (descriptor_ < 0) throw std::logic_error("AtomicFile::write after commit or failure ('" + path_ + "')");
  const char* from = static_cast<const char*>(data);
  while (size > 0) {
    const ssize_t done = ::write(descriptor_, from, size);
    if (done < 0) {
      if (errno == EINTR) continue;
      fail(systemReason(errno));
    }
    if (done == 0) fail("the file system accepted no more bytes");  // write() of > 0 bytes never returns 0 otherwise
    from += done;
    size -= static_cast<std::size_t>(done);
    written_ += static_cast<std::size_t>(done);
  }
}

void AtomicFile::commit() {
  if (descriptor_ < 0) throw std::logic_error("AtomicFile::commit twice or after a failure ('" + path_ + "')");
  // A delayed allocation (ext4, XFS, NFS) reports a full disk or a quota only here. EINVAL: a
  // file system that cannot sync (it then has nothing of this file to lose either).
  if (::fdatasync(descriptor_) != 0 && errno != EINVAL) fail(systemReason(errno));
  struct stat status {};
  if (::fstat(descriptor_, &status) != 0) fail(systemReason(errno));
  if (static_cast<std::size_t>(status.st_size) != written_) {
    fail("the file has " + std::to_string(status.st_size) + " of the " + std::to_string(written_) +
         " bytes written");
  }
  const int closed = ::close(descriptor_);
  descriptor_ = -1;
  if (closed != 0) fail(systemReason(errno));
  if (::rename(temporary_.c_str(), path_.c_str()) != 0) fail(systemReason(errno));
  temporary_.clear();
}

void writeFileAtomically(const std::string& path, const void* data, std::size_t size) {
  AtomicFile file(path);
  file.write(data, size);
  file.commit();
}

void writeFileAtomically(const std::string& path, const std::string& bytes) {
  writeFileAtomically(path, bytes.data(), bytes.size());
}

std::string temporaryPathFor(const std::string& path, long pid) { return temporaryName(path, pid, 0); }

std::string temporaryPathFor(const std::string& path) { return temporaryPathFor(path, static_cast<long>(::getpid())); }

std::optional<TemporaryName> parseTemporaryName(const std::string& fileName) {
  // ".stem.tmpPID[-N].ext"; the stem may hold dots and ".tmp" itself (a temporary of a temporary).
  static const std::regex name(R"(\.(.+)\.tmp([0-9]{1,9})(-[0-9]{1,4})?(\.[^.]*)?)");
  std::smatch match;
  if (!std::regex_match(fileName, match, name)) return std::nullopt;
  TemporaryName parsed;
  parsed.output = match[1].str() + match[4].str();
  parsed.pid = std::stol(match[2].str());
  return parsed;
}

bool processAlive(long pid) {
  // EPERM: it exists but belongs to another user.
  return pid > 0 && (::kill(static_cast<pid_t>(pid), 0) == 0 || errno == EPERM);
}

void discardTemporary(const std::string& temporary) noexcept {
  if (!temporary.empty()) ::unlink(temporary.c_str());
}

}  // namespace io
}  // namespace lidar_sgm
