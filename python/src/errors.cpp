#include "errors.hpp"

#include <exception>
#include <stdexcept>
#include <string>

namespace lidar_sgm {
namespace python {

namespace {

/// Sets `type` with the C++ message. A message may quote bytes of the file it is about (a binary
/// file given as a text one): those that are not UTF-8 are kept as \xNN escapes, where
/// PyErr_SetString would fail to decode them and leave an exception without any message.
void setError(PyObject* type, const char* message) {
  PyObject* text = PyUnicode_DecodeUTF8(message, static_cast<Py_ssize_t>(std::char_traits<char>::length(message)),
                                        "backslashreplace");
  if (text == nullptr) return;  // out of memory: that error is set instead
  PyErr_SetObject(type, text);
  Py_DECREF(text);
}

}  // namespace

void registerErrors(pybind11::module_& /*module*/) {
  pybind11::register_exception_translator([](std::exception_ptr error) {
    try {
      if (error) std::rethrow_exception(error);
    } catch (const FileError& e) {
      setError(PyExc_OSError, e.what());
    } catch (const std::invalid_argument& e) {  // as pybind11's own translation, with setError's decoding
      setError(PyExc_ValueError, e.what());
    }
  });
}

}  // namespace python
}  // namespace lidar_sgm
