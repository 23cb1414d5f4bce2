#pragma once
// All-or-nothing outputs for the tools that write several files from one run: each
// output is written to a hidden temporary beside it, and the temporaries are renamed into place
// only when every one of them was written. A failure, an exception or SIGINT/SIGTERM leaves the
// user's files as they were and no temporary behind.

#include <string>
#include <vector>

namespace lidar_sgm {
namespace io {

class OutputTransaction {
 public:
  /// Checks every output before any work: its folder exists and can be written (a probe file is
  /// created and removed there, which also answers for read-only file systems and root), and the
  /// output is not a folder. Removes the temporaries that an earlier run, no longer alive, left
  /// for these outputs. Registers this run's temporaries for removal on SIGINT and SIGTERM.
  /// Throws std::invalid_argument naming the output and the problem.
  explicit OutputTransaction(std::vector<std::string> outputs);
  /// Removes every temporary not committed (an exception unwinding, a failed write).
  ~OutputTransaction();
  OutputTransaction(const OutputTransaction&) = delete;
  OutputTransaction& operator=(const OutputTransaction&) = delete;

  /// Where to write `output` (one given to the constructor): ".<stem>.tmp<pid><ext>" beside it,
  /// the name the library's own writers use, so format-by-extension writers still work.
  const std::string& temporary(const std::string& output) const;

  /// Calls `writer(temporary(output))`; an exception it throws is rethrown as std::runtime_error
  /// "cannot write '<output>': <reason>" (naming the user's file, not the temporary).
  template <typename Writer>
  void write(const std::string& output, Writer&& writer) {
    const std::string& path = temporary(output);
    try {
      writer(path);
    } catch (const std::exception& e) {
      rethrowNamingOutput(output, path, e.what());
    }
  }

  /// Renames every temporary into place, after checking that all of them exist. Throws
  /// std::runtime_error naming the output that was not written (nothing is renamed then).
  void commit();

 private:
  [[noreturn]] static void rethrowNamingOutput(const std::string& output, const std::string& temporary,
                                               const std::string& what);

  std::vector<std::string> outputs_;
  std::vector<std::string> temporaries_;
  bool committed_ = false;
};

/// The hidden temporaries of `output` that a run no longer alive left (".<stem>.tmp<pid><ext>"
/// from this class or the library's writers, and the writers' own temporary of such a file),
/// removed; returns how many. A temporary of a live process is left alone.
std::size_t removeDeadRunTemporaries(const std::string& output);

}  // namespace io
}  // namespace lidar_sgm
