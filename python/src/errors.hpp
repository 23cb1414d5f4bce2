#pragma once
// The library's errors as Python exceptions: std::invalid_argument -> ValueError, a file that
// cannot be read -> OSError, each with the C++ message (bytes that are not UTF-8 as \xNN escapes).

#include <stdexcept>
#include <string>

#include <pybind11/pybind11.h>

namespace lidar_sgm {
namespace python {

/// A file that is missing, unreadable or malformed; becomes OSError.
class FileError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Registers FileError -> OSError with the module.
void registerErrors(pybind11::module_& module);

/// Runs a reader of files: its std::runtime_error (the io readers' "missing, unreadable or
/// malformed" errors, which name the file) becomes FileError; std::invalid_argument passes on.
template <typename Read>
auto readingFile(Read&& read) -> decltype(read()) {
  try {
    return read();
  } catch (const std::invalid_argument&) {
    throw;
  } catch (const std::runtime_error& e) {
    throw FileError(e.what());
  }
}

}  // namespace python
}  // namespace lidar_sgm
