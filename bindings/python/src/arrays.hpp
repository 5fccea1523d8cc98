// numpy arrays in: checked without copying, refused with a message that names the
// argument, the expected shape, dtype and strides, and what was given.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "bindings.hpp"

namespace finflex::python {

// The parameter rows of a job: a finflex.Parameters of the model, or an object with
// the buffer protocol (a numpy array) of float32, shape (instances,
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
  ParameterView view_;
  Py_buffer buffer_{};
  bool held_ = false;
};

// A copy of an (n, columns) array of float32 (any strides) as n * columns floats.
std::vector<float> float_rows(nb::handle array, const char* name, std::size_t columns);
// The same into `rows` (resized; its memory reused by a frame's call).
void float_rows_into(nb::handle array, const char* name, std::size_t columns,
                     std::vector<float>& rows);
// The rows of an (n, columns) float32 array: the array's own memory when they lie one
// after the other (C order; valid while it lives and is not resized), else `copy`
// (resized, as float_rows_into fills it); `rows` gets n. Other arrays are rejected as
// float_rows_into rejects them.
const float* float_rows_in_place(nb::handle array, const char* name, std::size_t columns,
                                 std::vector<float>& copy, std::size_t& rows);
// A copy of an (n, columns) array of uint32 (any strides).
std::vector<std::uint32_t> index_rows(nb::handle array, const char* name, std::size_t columns);

}  // namespace finflex::python
