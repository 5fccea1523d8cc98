// numpy arrays in: checked without copying, refused with a message that names the
// argument, the expected shape, dtype and strides, and what was given.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "bindings.hpp"

namespace finflex::python {

// Imports numpy's C API (once, at module import; throws the Python error).
void import_numpy();

// The parameter rows of a job: a finflex.Parameters of the model, or a numpy array (or
// another object with the buffer protocol) of float32, shape (instances,
// model.values_per_instance), whose rows are contiguous (any row stride of at least a
// row; rows may be a slice of a wider array). No copy: view() points at the object's
// memory, held (the buffer exported) until this object goes. Needs the GIL to make
// and to destroy.
class ParameterArgument {
 public:
  ParameterArgument(nb::handle parameters, const RiggedMesh& model);
  ~ParameterArgument();
  ParameterArgument(const ParameterArgument&) = delete;
  ParameterArgument& operator=(const ParameterArgument&) = delete;

  const ParameterView& view() const { return view_; }

 private:
  // Checks rows of `shape` and byte `strides` at `data` and points view_ at them.
  void set_rows(nb::handle parameters, const std::string& expected, void* data,
                const Py_ssize_t* shape, const Py_ssize_t* strides, std::size_t values);

  ParameterView view_;
  Py_buffer buffer_{};
  bool held_ = false;
};

// A copy of an (n, columns) array of float32 (any strides) as n * columns floats.
std::vector<float> float_rows(nb::handle array, const char* name, std::size_t columns);
// A copy of an (n, columns) array of uint32 (any strides).
std::vector<std::uint32_t> index_rows(nb::handle array, const char* name, std::size_t columns);

}  // namespace finflex::python
