// finflex.Error (finflex/_error.py): the library's finflex::Error as a Python exception
// with its message, code and field, raised for every error the module reports.
#include <exception>

#include "bindings.hpp"

namespace finflex::python {
namespace {

PyObject* error_type = nullptr;

void raise(const char* code, const std::string& field, const char* message) {
  nb::object error =
      nb::steal(PyObject_CallFunction(error_type, "sss", message, code, field.c_str()));
  if (!error.is_valid()) return;  // the call set its own exception
  PyErr_SetObject(error_type, error.ptr());
}

void translate(const std::exception_ptr& exception, void*) {
  try {
    std::rethrow_exception(exception);
  } catch (const Error& e) {
    raise(error_code_name(e.code()), e.field(), e.what());
  }
}

}  // namespace

void reject(const std::string& field, const std::string& message) {
  throw Error(ErrorCode::kInvalidArgument, field, message);
}

void bind_errors(nb::module_& m) {
  // The class is Python's own (finflex/_error.py); the module keeps it for good.
  nb::object type = nb::module_::import_("finflex._error").attr("Error");
  error_type = type.release().ptr();
  m.attr("Error") = nb::handle(error_type);
  nb::register_exception_translator(translate);
}

}  // namespace finflex::python
