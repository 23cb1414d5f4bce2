#pragma once
// Running a tool as a user does, from the shell, for the tests of the command-line tools.

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <string>

namespace lidar_sgm {
namespace test {

struct CommandResult {
  int exitCode;        ///< -1 when the command did not exit normally (an abort, a signal)
  std::string output;  ///< what it printed on stdout (stderr too where the command redirects it)
};

/// Runs `command` with /bin/sh (popen) and waits for it.
inline CommandResult runCommand(const std::string& command) {
  FILE* pipe = popen(command.c_str(), "r");
  std::string output;
  std::array<char, 512> buffer{};
  while (pipe && fgets(buffer.data(), buffer.size(), pipe)) output += buffer.data();
  const int status = pipe ? pclose(pipe) : -1;
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, output};
}

}  // namespace test
}  // namespace lidar_sgm
