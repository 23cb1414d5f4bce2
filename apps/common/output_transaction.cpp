#include "common/output_transaction.hpp"

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <regex>
#include <stdexcept>
#include <system_error>

namespace fs = std::filesystem;

namespace lidar_sgm {
namespace apps {
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

/// ".<stem>.tmp<pid><ext>": the temporary a write of `path` goes through (src/io/atomic_file.cpp
/// names the library's the same way).
fs::path temporaryOf(const fs::path& path) {
  fs::path temporary(path);
  temporary.replace_filename("." + path.stem().string() + ".tmp" + std::to_string(::getpid()) +
                             path.extension().string());
  return temporary;
}

std::string regexEscaped(const std::string& text) {
  static const std::regex special(R"([.^$|()\[\]{}*+?\\])");
  return std::regex_replace(text, special, R"(\$&)");
}

bool processAlive(long pid) { return pid > 0 && (::kill(static_cast<pid_t>(pid), 0) == 0 || errno != ESRCH); }

/// Creates and removes a file in `folder`: the only check that answers for permissions, ACLs,
/// read-only mounts and a root user alike.
void probeWritable(const std::string& output, const fs::path& folder) {
  const fs::path probe = folder / (".lidar_sgm_probe.tmp" + std::to_string(::getpid()));
  std::ofstream file(probe);
  const bool ok = static_cast<bool>(file);
  file.close();
  std::error_code ignored;
  fs::remove(probe, ignored);
  if (!ok) {
    throw std::invalid_argument("cannot write '" + output + "': the folder '" + folder.string() +
                                "' is not writable (" + std::strerror(errno) + ")");
  }
}

}  // namespace

std::size_t removeDeadRunTemporaries(const std::string& output) {
  const fs::path path = fs::absolute(output).lexically_normal();
  // ".stem.tmpPID.ext", or the library writer's own temporary of that file: "..stem.tmpPID.tmpPID.ext".
  const std::regex name(R"(\.?\.)" + regexEscaped(path.stem().string()) + R"(\.tmp([0-9]+)(\.tmp[0-9]+)?)" +
                        regexEscaped(path.extension().string()));
  std::size_t removed = 0;
  std::error_code ec;
  for (fs::directory_iterator it(path.parent_path(), ec), end; !ec && it != end; it.increment(ec)) {
    std::smatch match;
    const std::string file = it->path().filename().string();
    if (!std::regex_match(file, match, name)) continue;
    if (processAlive(std::stol(match[1].str().substr(0, 18)))) continue;
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

}  // namespace apps
}  // namespace lidar_sgm
