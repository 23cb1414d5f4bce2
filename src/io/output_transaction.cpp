#include "lidar_sgm/io/output_transaction.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <system_error>

#include "lidar_sgm/io/atomic_file.hpp"

namespace fs = std::filesystem;

namespace lidar_sgm {
namespace io {
namespace {

// The names the signal handler removes. Fixed storage: a handler may only call async-signal-safe
// functions (unlink), so nothing here is allocated or freed while a signal can arrive.
constexpr int kMaxTemporaries = 64;
constexpr std::size_t kMaxPathBytes = 4096;
char registered[kMaxTemporaries][kMaxPathBytes];
volatile std::sig_atomic_t registeredCount = 0;

extern "C" void removeTemporariesAndDie(int signal) {
  for (int i = 0; i < registeredCount; ++i) ::unlink(registered[i]);
  // Dies of the same signal, so the caller sees "killed by SIGINT" (exit status 128 + signal).
  std::signal(signal, SIG_DFL);
  std::raise(signal);
}

void registerForSignals(const std::string& path) {
  if (registeredCount >= kMaxTemporaries || path.size() >= kMaxPathBytes) {
    throw std::invalid_argument("too many or too long output paths ('" + path + "')");
  }
  std::memcpy(registered[registeredCount], path.c_str(), path.size() + 1);
  registeredCount = registeredCount + 1;
  struct sigaction action {};
  action.sa_handler = removeTemporariesAndDie;
  sigemptyset(&action.sa_mask);
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
}

void unregisterAll() {
  registeredCount = 0;
  std::signal(SIGINT, SIG_DFL);
  std::signal(SIGTERM, SIG_DFL);
}

/// The temporary a write of `path` goes through in this process (io::temporaryPathFor's name).
fs::path temporaryOf(const fs::path& path) { return io::temporaryPathFor(path.string()); }

/// Creates and removes a file in `folder`: the only check that answers for permissions, ACLs,
/// read-only mounts and a root user alike.
void probeWritable(const std::string& output, const fs::path& folder) {
  const fs::path probe = folder / (".lidar_sgm_probe.tmp" + std::to_string(::getpid()));
  // open(2) itself, so that errno is the kernel's answer (EPERM, EROFS, EACCES...), not a later call's.
  const int descriptor = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0600);
  const int error = errno;
  if (descriptor >= 0) {
    ::close(descriptor);
    ::unlink(probe.c_str());
    return;
  }
  throw std::invalid_argument("cannot write '" + output + "': the folder '" + folder.string() +
                              "' is not writable (" + std::strerror(error) + ")");
}

}  // namespace

std::size_t removeDeadRunTemporaries(const std::string& output) {
  const fs::path path = fs::absolute(output).lexically_normal();
  const std::string target = path.filename().string();
  std::size_t removed = 0;
  std::error_code ec;
  for (fs::directory_iterator it(path.parent_path(), ec), end; !ec && it != end; it.increment(ec)) {
    // ".stem.tmpPID.ext", or a writer's own temporary of that file: "..stem.tmpPID.tmpPID2.ext".
    const std::optional<io::TemporaryName> name = io::parseTemporaryName(it->path().filename().string());
    if (!name) continue;
    const std::optional<io::TemporaryName> outer =
        name->output == target ? std::nullopt : io::parseTemporaryName(name->output);
    if (name->output != target && !(outer && outer->output == target)) continue;
    if (io::processAlive(name->pid) || (outer && io::processAlive(outer->pid))) continue;
    std::error_code removeError;
    if (fs::remove(it->path(), removeError)) ++removed;
  }
  return removed;
}

OutputTransaction::OutputTransaction(std::vector<std::string> outputs) : outputs_(std::move(outputs)) {
  for (const std::string& output : outputs_) {
    const fs::path folder = fs::absolute(output).parent_path();
    std::error_code ec;
    if (!fs::is_directory(folder, ec)) {
      throw std::invalid_argument("cannot write '" + output + "': the folder '" + folder.string() + "' does not exist");
    }
    if (fs::is_directory(output, ec)) throw std::invalid_argument("cannot write '" + output + "': it is a folder");
    if (fs::exists(output, ec) && !fs::is_regular_file(output, ec)) {
      throw std::invalid_argument("cannot write '" + output + "': it exists and is not a regular file");
    }
    probeWritable(output, folder);
    removeDeadRunTemporaries(output);
  }
  for (const std::string& output : outputs_) {
    const fs::path temporary = temporaryOf(output);
    temporaries_.push_back(temporary.string());
    registerForSignals(temporaries_.back());
    registerForSignals(temporaryOf(temporary).string());  // the writer's own temporary of it
  }
}

OutputTransaction::~OutputTransaction() {
  if (!committed_) {
    for (const std::string& temporary : temporaries_) {
      std::error_code ignored;
      fs::remove(temporary, ignored);
      fs::remove(temporaryOf(temporary), ignored);
    }
  }
  unregisterAll();
}

const std::string& OutputTransaction::temporary(const std::string& output) const {
  const auto it = std::find(outputs_.begin(), outputs_.end(), output);
  if (it == outputs_.end()) throw std::logic_error("OutputTransaction: '" + output + "' is not an output of this run");
  return temporaries_[static_cast<std::size_t>(it - outputs_.begin())];
}

void OutputTransaction::rethrowNamingOutput(const std::string& output, const std::string& temporary,
                                            const std::string& what) {
  // The writers say "cannot write '<temporary>': <reason>"; the user knows the output's name.
  const std::string prefix = "cannot write '" + temporary + "': ";
  const std::string reason = what.rfind(prefix, 0) == 0 ? what.substr(prefix.size()) : what;
  throw std::runtime_error("cannot write '" + output + "': " + reason + "; no output was replaced");
}

void OutputTransaction::commit() {
  for (std::size_t i = 0; i < outputs_.size(); ++i) {
    std::error_code ec;
    if (!fs::is_regular_file(temporaries_[i], ec)) {
      throw std::runtime_error("cannot write '" + outputs_[i] + "': it was not written; no output was replaced");
    }
  }
  // Renames within one folder each: they do not fail once the files exist and the folders were
  // writable, so the outputs appear together.
  for (std::size_t i = 0; i < outputs_.size(); ++i) {
    std::error_code ec;
    fs::rename(temporaries_[i], outputs_[i], ec);
    if (ec) throw std::runtime_error("cannot write '" + outputs_[i] + "': " + ec.message());
  }
  committed_ = true;
}

}  // namespace io
}  // namespace lidar_sgm
