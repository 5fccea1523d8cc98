// numpy arrays in: checks and views.
#include "arrays.hpp"

#include <string>

#include <nanobind/ndarray.h>

namespace finflex::python {
namespace {

using AnyArray = nb::ndarray<nb::ro, nb::device::cpu>;

// str(object.<name>).
std::string attribute_text(nb::handle object, const char* name) {
  const nb::object value = object.attr(name);
  const nb::str text = nb::steal<nb::str>(PyObject_Str(value.ptr()));
  return text.is_valid() ? text.c_str() : "?";
}

// "float64 array of shape (100,) and byte strides (8,)" or the object's type name.
std::string describe(nb::handle object) {
  if (nb::hasattr(object, "dtype") && nb::hasattr(object, "shape")) {
    std::string text =
        attribute_text(object, "dtype") + " array of shape " + attribute_text(object, "shape");
    if (nb::hasattr(object, "strides"))
      text += " and byte strides " + attribute_text(object, "strides");
    return text;
  }
  return attribute_text(nb::handle(reinterpret_cast<PyObject*>(Py_TYPE(object.ptr()))), "__name__");
}

// The array behind `object` without conversion; rejects what is not a CPU array.
AnyArray as_array(nb::handle object, const std::string& name, const std::string& expected) {
  AnyArray array;
  if (!nb::try_cast(object, array, false)) {
    reject(name, name + ": expected " + expected + ", got " + describe(object));
  }
  return array;
}

// The (n, columns) array of T behind `object`; rejects any other.
template <typename T>
AnyArray rows_array(nb::handle object, const char* name, std::size_t columns, const char* dtype) {
  const std::string expected =
      std::string("a ") + dtype + " array of shape (n, " + std::to_string(columns) + ")";
  AnyArray array = as_array(object, name, expected);
  if (array.dtype() != nb::dtype<T>() || array.ndim() != 2 || array.shape(1) != columns) {
    reject(name, std::string(name) + ": expected " + expected + ", got " + describe(object));
  }
  return array;
}

// The rows of a checked (n, columns) array into `out`, whatever its strides.
template <typename T>
void copy_checked_rows(const AnyArray& array, std::size_t columns, std::vector<T>& out) {
  const T* data = static_cast<const T*>(array.data());
  out.resize(array.shape(0) * columns);
  for (std::size_t i = 0; i < array.shape(0); ++i) {
    for (std::size_t c = 0; c < columns; ++c) {
      out[i * columns + c] = data[static_cast<std::int64_t>(i) * array.stride(0) +
                                  static_cast<std::int64_t>(c) * array.stride(1)];
    }
  }
}

template <typename T>
void copy_rows(nb::handle object, const char* name, std::size_t columns, const char* dtype,
               std::vector<T>& out) {
  copy_checked_rows(rows_array<T>(object, name, columns, dtype), columns, out);
}

}  // namespace

ParameterArgument::ParameterArgument(nb::handle parameters, const RiggedMesh& model) {
  const std::size_t values = model.values_per_instance();
  if (nb::isinstance<PyParameters>(parameters)) {
    const PyParameters& p = nb::cast<const PyParameters&>(parameters);
    if (p.values.values_per_instance() != values) {
      reject("parameters", "parameters: a finflex.Parameters of " +
                               std::to_string(p.values.values_per_instance()) +
                               " values per instance, the model reads " + std::to_string(values));
    }
    view_ = p.values.view();
    return;
  }
  const std::string expected = "a float32 array of shape (instances, " + std::to_string(values) +
                               ") with contiguous rows, or a finflex.Parameters";
  // The buffer protocol: the cheapest way to a numpy array's memory (a frame's call).
  if (PyObject_GetBuffer(parameters.ptr(), &buffer_, PyBUF_RECORDS_RO) != 0) {
    PyErr_Clear();
    reject("parameters", "parameters: expected " + expected + ", got " + describe(parameters));
  }
  held_ = true;
  const std::string format = buffer_.format == nullptr ? "B" : buffer_.format;
  const bool is_float32 = buffer_.itemsize == 4 &&
                          (format == "f" || format == "<f" || format == "=f" || format == "@f");
  if (!is_float32) {
    reject("parameters", "parameters: expected " + expected + ", got " + describe(parameters) +
                             " (convert with .astype(numpy.float32))");
  }
  if (buffer_.ndim != 2 || static_cast<std::size_t>(buffer_.shape[1]) != values) {
    reject("parameters", "parameters: expected " + expected + ", got " + describe(parameters) +
                             " (the model's parameters: " + std::to_string(values) +
                             " values per instance)");
  }
  const std::size_t instances = static_cast<std::size_t>(buffer_.shape[0]);
  const Py_ssize_t row_bytes = static_cast<Py_ssize_t>(4 * values);
  const bool rows_contiguous = values <= 1 || buffer_.strides[1] == 4;
  const bool rows_apart =
      instances <= 1 || (buffer_.strides[0] >= row_bytes && buffer_.strides[0] % 4 == 0);
  if (!rows_contiguous || !rows_apart) {
    reject("parameters", "parameters: expected " + expected + ", got " + describe(parameters) +
                             ": each row's values must be adjacent and rows must not overlap "
                             "(copy with numpy.ascontiguousarray)");
  }
  if (reinterpret_cast<std::uintptr_t>(buffer_.buf) % alignof(float) != 0) {
    reject("parameters",
           "parameters: the array's data is not aligned to 4 bytes (copy with "
           "numpy.ascontiguousarray)");
  }
  const std::size_t stride =
      instances <= 1 ? values : static_cast<std::size_t>(buffer_.strides[0] / 4);
  view_ = ParameterView{static_cast<const float*>(buffer_.buf), instances, stride};
}

ParameterArgument::~ParameterArgument() {
  if (held_) PyBuffer_Release(&buffer_);
}

std::vector<float> float_rows(nb::handle array, const char* name, std::size_t columns) {
  std::vector<float> rows;
  float_rows_into(array, name, columns, rows);
  return rows;
}

void float_rows_into(nb::handle array, const char* name, std::size_t columns,
                     std::vector<float>& rows) {
  copy_rows<float>(array, name, columns, "float32", rows);
}

const float* float_rows_in_place(nb::handle array, const char* name, std::size_t columns,
                                 std::vector<float>& copy, std::size_t& rows) {
  const AnyArray checked = rows_array<float>(array, name, columns, "float32");
  rows = checked.shape(0);
  const bool contiguous = (rows <= 1 || checked.stride(0) == static_cast<std::int64_t>(columns)) &&
                          (columns <= 1 || checked.stride(1) == 1);
  if (contiguous) return static_cast<const float*>(checked.data());
  copy_checked_rows(checked, columns, copy);
  return copy.data();
}

std::vector<std::uint32_t> index_rows(nb::handle array, const char* name, std::size_t columns) {
  std::vector<std::uint32_t> rows;
  copy_rows<std::uint32_t>(array, name, columns, "uint32", rows);
  return rows;
}

}  // namespace finflex::python
