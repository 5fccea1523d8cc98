// glTF accessors: bounds-checked views of buffer data, read as floats or indices.
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "finflex/error.hpp"
#include "io/gltf.hpp"

namespace finflex::io {
namespace {

const char* component_type_name(int component_type) {
  switch (component_type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
      return "byte";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return "unsigned byte";
    case TINYGLTF_COMPONENT_TYPE_SHORT:
      return "short";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
      return "unsigned short";
    case TINYGLTF_COMPONENT_TYPE_INT:
      return "int";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
      return "unsigned int";
    case TINYGLTF_COMPONENT_TYPE_FLOAT:
      return "float";
    default:
      return "unknown";
  }
}

const char* type_name(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR:
      return "SCALAR";
    case TINYGLTF_TYPE_VEC2:
      return "VEC2";
    case TINYGLTF_TYPE_VEC3:
      return "VEC3";
    case TINYGLTF_TYPE_VEC4:
      return "VEC4";
    case TINYGLTF_TYPE_MAT2:
      return "MAT2";
    case TINYGLTF_TYPE_MAT3:
      return "MAT3";
    case TINYGLTF_TYPE_MAT4:
      return "MAT4";
    default:
      return "unknown";
  }
}

// ---------------------------------------------------------------------------------
// Accessors

// Where an accessor's elements lie: element i, component c starts at
// data + i * stride + c * component_size. data is null for an accessor without
// bufferView (all zeros, as the spec says).
struct AccessorView {
  const unsigned char* data = nullptr;
  std::size_t count = 0;
  std::size_t stride = 0;
  std::size_t component_size = 0;
  int component_type = 0;
  int components = 0;
  bool normalized = false;
};

// Resolves accessor `index` with bounds checks against its bufferView and buffer, or,
// without bufferView, against the input's size. `field` names the referring property
// (e.g. "meshes[0].primitives[1].NORMAL").
AccessorView view_accessor(const LoadedGltf& gltf, int index, int expected_type,
                           const std::string& field) {
  const tinygltf::Model& model = gltf.model;
  if (index < 0 || static_cast<std::size_t>(index) >= model.accessors.size()) {
    throw_gltf_format(field, "accessor " + std::to_string(index) + " does not exist (" +
                                 std::to_string(model.accessors.size()) + " accessors)");
  }
  const tinygltf::Accessor& accessor = model.accessors[static_cast<std::size_t>(index)];
  const std::string where = "accessor " + std::to_string(index);
  if (accessor.sparse.isSparse) {
    throw_gltf_format(field, where + " is sparse (sparse accessors are not supported)");
  }
  if (accessor.type != expected_type) {
    throw_gltf_format(field, where + " has type " + type_name(accessor.type) + ", expected " +
                                 type_name(expected_type));
  }
  const int component_size =
      tinygltf::GetComponentSizeInBytes(static_cast<std::uint32_t>(accessor.componentType));
  if (component_size <= 0 || accessor.componentType == TINYGLTF_COMPONENT_TYPE_DOUBLE) {
    throw_gltf_format(
        field, where + " has unknown componentType " + std::to_string(accessor.componentType));
  }
  AccessorView view;
  view.count = accessor.count;
  view.component_type = accessor.componentType;
  view.components = tinygltf::GetNumComponentsInType(static_cast<std::uint32_t>(expected_type));
  view.component_size = static_cast<std::size_t>(component_size);
  view.normalized = accessor.normalized;
  const std::size_t element_size = view.component_size * static_cast<std::size_t>(view.components);
  if (accessor.bufferView < 0) {  // no data: zeros, as many as the input's bytes at most
    if (view.count > gltf.input_bytes) {
      throw_gltf_format(field, where + " has no bufferView (all zeros) and count " +
                                   std::to_string(view.count) + ", more than the " +
                                   std::to_string(gltf.input_bytes) + " bytes of input allow");
    }
    view.stride = element_size;
    return view;
  }
  if (static_cast<std::size_t>(accessor.bufferView) >= model.bufferViews.size()) {
    throw_gltf_format(field, where + " refers to bufferView " +
                                 std::to_string(accessor.bufferView) + ", which does not exist");
  }
  const tinygltf::BufferView& buffer_view =
      model.bufferViews[static_cast<std::size_t>(accessor.bufferView)];
  if (buffer_view.buffer < 0 ||
      static_cast<std::size_t>(buffer_view.buffer) >= model.buffers.size()) {
    throw_gltf_format(field, "bufferView " + std::to_string(accessor.bufferView) +
                                 " refers to buffer " + std::to_string(buffer_view.buffer) +
                                 ", which does not exist");
  }
  const std::vector<unsigned char>& bytes =
      model.buffers[static_cast<std::size_t>(buffer_view.buffer)].data;
  if (buffer_view.byteOffset > bytes.size() ||
      buffer_view.byteLength > bytes.size() - buffer_view.byteOffset) {
    throw_gltf_format(field, "bufferView " + std::to_string(accessor.bufferView) + " (byteOffset " +
                                 std::to_string(buffer_view.byteOffset) + ", byteLength " +
                                 std::to_string(buffer_view.byteLength) +
                                 ") exceeds its buffer of " + std::to_string(bytes.size()) +
                                 " bytes");
  }
  view.stride = buffer_view.byteStride != 0 ? buffer_view.byteStride : element_size;
  if (view.stride < element_size) {
    throw_gltf_format(field, "bufferView " + std::to_string(accessor.bufferView) + " byteStride " +
                                 std::to_string(view.stride) + " is smaller than the element (" +
                                 std::to_string(element_size) + " bytes)");
  }
  if (view.count > 0) {
    const std::size_t available = buffer_view.byteLength;
    const bool fits =
        accessor.byteOffset <= available &&
        (view.count - 1) <= (available - accessor.byteOffset) / view.stride &&
        accessor.byteOffset + (view.count - 1) * view.stride + element_size <= available;
    if (!fits) {
      throw_gltf_format(field, where + " (byteOffset " + std::to_string(accessor.byteOffset) +
                                   ", count " + std::to_string(view.count) + ", stride " +
                                   std::to_string(view.stride) + ") exceeds bufferView " +
                                   std::to_string(accessor.bufferView) + " of " +
                                   std::to_string(available) + " bytes");
    }
  }
  view.data = bytes.data() + buffer_view.byteOffset + accessor.byteOffset;
  return view;
}

template <typename T>
T load_component(const AccessorView& view, std::size_t element, int component) {
  T value;
  std::memcpy(
      &value,
      view.data + element * view.stride + static_cast<std::size_t>(component) * view.component_size,
      sizeof(T));
  return value;
}

// Throws kInvalidMesh for the first non-finite value, naming the accessor element
// (e.g. "meshes[0].primitives[0].POSITION[1].y"): checked before any transform,
// which would smear a NaN over all components.
void check_finite(const std::vector<float>& values, int components, const std::string& field) {
  const char* const names = components == 2 ? "uv" : "xyzw";
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (std::isfinite(values[i])) continue;
    const std::size_t n = static_cast<std::size_t>(components);
    const std::string element = indexed(field, i / n) + "." + names[i % n];
    throw Error(ErrorCode::kInvalidMesh, element,
                element + " is " +
                    (std::isnan(values[i]) ? "NaN"
                     : values[i] > 0       ? "+inf"
                                           : "-inf"));
  }
}

}  // namespace

std::vector<float> read_floats(const LoadedGltf& gltf, int index, int type, bool allow_normalized,
                               const std::string& field) {
  const AccessorView view = view_accessor(gltf, index, type, field);
  const bool is_float = view.component_type == TINYGLTF_COMPONENT_TYPE_FLOAT;
  const bool is_unorm = allow_normalized && view.normalized &&
                        (view.component_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                         view.component_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT);
  if (!is_float && !is_unorm) {
    throw_gltf_format(field, "accessor " + std::to_string(index) + " has componentType " +
                                 component_type_name(view.component_type) +
                                 (view.normalized ? " (normalized)" : "") + ", expected float" +
                                 (allow_normalized ? " or normalized unsigned byte/short" : ""));
  }
  std::vector<float> values(view.count * static_cast<std::size_t>(view.components), 0.0f);
  if (view.data == nullptr) return values;
  std::size_t out = 0;
  for (std::size_t i = 0; i < view.count; ++i) {
    for (int c = 0; c < view.components; ++c, ++out) {
      if (is_float) {
        values[out] = load_component<float>(view, i, c);
      } else if (view.component_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE) {
        values[out] = static_cast<float>(load_component<std::uint8_t>(view, i, c)) / 255.0f;
      } else {
        values[out] = static_cast<float>(load_component<std::uint16_t>(view, i, c)) / 65535.0f;
      }
    }
  }
  check_finite(values, view.components, field);
  return values;
}

std::vector<std::uint32_t> read_indices(const LoadedGltf& gltf, int index,
                                        const std::string& field) {
  const AccessorView view = view_accessor(gltf, index, TINYGLTF_TYPE_SCALAR, field);
  const int type = view.component_type;
  if (type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
      type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
      type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT) {
    throw_gltf_format(field, "accessor " + std::to_string(index) + " has componentType " +
                                 component_type_name(type) +
                                 ", expected unsigned byte, short or int");
  }
  std::vector<std::uint32_t> indices(view.count, 0);
  if (view.data == nullptr) return indices;
  for (std::size_t i = 0; i < view.count; ++i) {
    if (type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE) {
      indices[i] = load_component<std::uint8_t>(view, i, 0);
    } else if (type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT) {
      indices[i] = load_component<std::uint16_t>(view, i, 0);
    } else {
      indices[i] = load_component<std::uint32_t>(view, i, 0);
    }
  }
  return indices;
}

}  // namespace finflex::io
