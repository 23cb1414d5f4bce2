#include "errors.hpp"

#include <exception>

namespace lidar_sgm {
namespace python {

void registerErrors(pybind11::module_& /*module*/) {
  pybind11::register_exception_translator([](std::exception_ptr error) {
    try {
      if (error) std::rethrow_exception(error);
    } catch (const FileError& e) {
      PyErr_SetString(PyExc_OSError, e.what());
    }
  });
}

}  // namespace python
}  // namespace lidar_sgm
