// glTF 2.0 (.gltf) and GLB (.glb) through tinygltf.
//
// Reading flattens the scene into one Mesh: every node that carries a mesh adds the
// TRIANGLES primitives of that mesh, in depth-first node order, transformed to world
// space; each primitive becomes a FaceGroup named "<mesh name or index>/<primitive
// index>". Writing produces one mesh, one primitive, one node without transform.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <string>
#include <string_view>
#include <vector>

#include "finflex/error.hpp"
#include "mesh_io_formats.hpp"
#include "mesh_io_gltf.hpp"

namespace finflex::io {
namespace {

// ---------------------------------------------------------------------------------
// Errors

[[noreturn]] void throw_format(const std::string& field, const std::string& message) {
  throw Error(ErrorCode::kFormat, field, field + ": " + message);
}

std::string indexed(const std::string& array, std::size_t index) {
  return array + "[" + std::to_string(index) + "]";
}

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

const char* mode_name(int mode) {
  switch (mode) {
    case TINYGLTF_MODE_POINTS:
      return "POINTS";
    case TINYGLTF_MODE_LINE:
      return "LINES";
    case TINYGLTF_MODE_LINE_LOOP:
      return "LINE_LOOP";
    case TINYGLTF_MODE_LINE_STRIP:
      return "LINE_STRIP";
    case TINYGLTF_MODE_TRIANGLES:
      return "TRIANGLES";
    case TINYGLTF_MODE_TRIANGLE_STRIP:
      return "TRIANGLE_STRIP";
    case TINYGLTF_MODE_TRIANGLE_FAN:
      return "TRIANGLE_FAN";
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

// Resolves accessor `index` with bounds checks against its bufferView and buffer.
// `field` names the referring property (e.g. "meshes[0].primitives[1].NORMAL").
AccessorView view_accessor(const tinygltf::Model& model, int index, int expected_type,
                           const std::string& field) {
  if (index < 0 || static_cast<std::size_t>(index) >= model.accessors.size()) {
    throw_format(field, "accessor " + std::to_string(index) + " does not exist (" +
                            std::to_string(model.accessors.size()) + " accessors)");
  }
  const tinygltf::Accessor& accessor = model.accessors[static_cast<std::size_t>(index)];
  const std::string where = "accessor " + std::to_string(index);
  if (accessor.sparse.isSparse) {
    throw_format(field, where + " is sparse (sparse accessors are not supported)");
  }
  if (accessor.type != expected_type) {
    throw_format(field, where + " has type " + type_name(accessor.type) + ", expected " +
                            type_name(expected_type));
  }
  const int component_size =
      tinygltf::GetComponentSizeInBytes(static_cast<std::uint32_t>(accessor.componentType));
  if (component_size <= 0 || accessor.componentType == TINYGLTF_COMPONENT_TYPE_DOUBLE) {
    throw_format(field,
                 where + " has unknown componentType " + std::to_string(accessor.componentType));
  }
  AccessorView view;
  view.count = accessor.count;
  view.component_type = accessor.componentType;
  view.components = tinygltf::GetNumComponentsInType(static_cast<std::uint32_t>(expected_type));
  view.component_size = static_cast<std::size_t>(component_size);
  view.normalized = accessor.normalized;
  const std::size_t element_size = view.component_size * static_cast<std::size_t>(view.components);
  if (accessor.bufferView < 0) {  // no data: zeros
    view.stride = element_size;
    return view;
  }
  if (static_cast<std::size_t>(accessor.bufferView) >= model.bufferViews.size()) {
    throw_format(field, where + " refers to bufferView " + std::to_string(accessor.bufferView) +
                            ", which does not exist");
  }
  const tinygltf::BufferView& buffer_view =
      model.bufferViews[static_cast<std::size_t>(accessor.bufferView)];
  if (buffer_view.buffer < 0 ||
      static_cast<std::size_t>(buffer_view.buffer) >= model.buffers.size()) {
    throw_format(field, "bufferView " + std::to_string(accessor.bufferView) + " refers to buffer " +
                            std::to_string(buffer_view.buffer) + ", which does not exist");
  }
  const std::vector<unsigned char>& bytes =
      model.buffers[static_cast<std::size_t>(buffer_view.buffer)].data;
  if (buffer_view.byteOffset > bytes.size() ||
      buffer_view.byteLength > bytes.size() - buffer_view.byteOffset) {
    throw_format(field, "bufferView " + std::to_string(accessor.bufferView) + " (byteOffset " +
                            std::to_string(buffer_view.byteOffset) + ", byteLength " +
                            std::to_string(buffer_view.byteLength) + ") exceeds its buffer of " +
                            std::to_string(bytes.size()) + " bytes");
  }
  view.stride = buffer_view.byteStride != 0 ? buffer_view.byteStride : element_size;
  if (view.stride < element_size) {
    throw_format(field, "bufferView " + std::to_string(accessor.bufferView) + " byteStride " +
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
      throw_format(field, where + " (byteOffset " + std::to_string(accessor.byteOffset) +
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

// Reads a float attribute as count * components floats. Float components always;
// with `allow_normalized`, also normalized unsigned byte / short (mapped to [0, 1]).
// Non-finite values are rejected (check_finite).
std::vector<float> read_floats(const tinygltf::Model& model, int index, int type,
                               bool allow_normalized, const std::string& field) {
  const AccessorView view = view_accessor(model, index, type, field);
  const bool is_float = view.component_type == TINYGLTF_COMPONENT_TYPE_FLOAT;
  const bool is_unorm = allow_normalized && view.normalized &&
                        (view.component_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                         view.component_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT);
  if (!is_float && !is_unorm) {
    throw_format(field, "accessor " + std::to_string(index) + " has componentType " +
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

// Reads an index accessor of unsigned byte, short or int components.
std::vector<std::uint32_t> read_indices(const tinygltf::Model& model, int index,
                                        const std::string& field) {
  const AccessorView view = view_accessor(model, index, TINYGLTF_TYPE_SCALAR, field);
  const int type = view.component_type;
  if (type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
      type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
      type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT) {
    throw_format(field, "accessor " + std::to_string(index) + " has componentType " +
                            component_type_name(type) + ", expected unsigned byte, short or int");
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

// ---------------------------------------------------------------------------------
// Scene flattening

// Unit vector along v, or v itself if it has zero length (validation reports it).
glm::dvec3 normalized_or_same(const glm::dvec3& v) {
  const double length = glm::length(v);
  return length > 0.0 ? v / length : v;
}

// A node's world transform and what it implies for normals, tangents and winding.
struct Transform {
  glm::dmat4 world{1.0};
  glm::dmat3 linear{1.0};         // upper 3x3: maps tangent directions
  glm::dmat3 normal_matrix{1.0};  // inverse transpose of linear: maps normals
  bool mirrors = false;           // negative determinant: flips winding and handedness

  explicit Transform(const glm::dmat4& m)
      : world(m),
        linear(m),
        normal_matrix(glm::transpose(glm::inverse(glm::dmat3(m)))),
        mirrors(glm::determinant(glm::dmat3(m)) < 0.0) {}
};

int find_attribute(const tinygltf::Primitive& primitive, const char* name) {
  const auto it = primitive.attributes.find(name);
  return it == primitive.attributes.end() ? -1 : it->second;
}

void check_count(const std::vector<float>& values, std::size_t components, std::size_t vertex_count,
                 const std::string& field) {
  if (values.size() == vertex_count * components) return;
  throw_format(field, "has " + std::to_string(values.size() / components) +
                          " elements, but POSITION has " + std::to_string(vertex_count));
}

// One TRIANGLES primitive as a Mesh in world space. Normals are the file's (through
// the normal matrix) or, if absent, area-weighted; `has_tangents` and
// `has_texcoords` tell whether the file gave them.
struct Part {
  Mesh mesh;
  bool has_tangents = false;
  bool has_texcoords = false;
  std::string group;  // its FaceGroup's name: "<mesh name or index>/<primitive index>"
};

Part read_primitive(const tinygltf::Model& model, const tinygltf::Primitive& primitive,
                    const Transform& transform, const std::string& field) {
  if (primitive.mode != TINYGLTF_MODE_TRIANGLES) {
    throw_format(field, std::string("mode ") + std::to_string(primitive.mode) + " (" +
                            mode_name(primitive.mode) + ") is not supported (only TRIANGLES)");
  }
  const int position_accessor = find_attribute(primitive, "POSITION");
  if (position_accessor < 0) throw_format(field, "has no POSITION attribute");
  const std::vector<float> positions =
      read_floats(model, position_accessor, TINYGLTF_TYPE_VEC3, false, field + ".POSITION");
  const std::size_t n = positions.size() / 3;

  Part part;
  Mesh& mesh = part.mesh;
  mesh.positions.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    const glm::dvec4 p(positions[3 * i], positions[3 * i + 1], positions[3 * i + 2], 1.0);
    mesh.positions.emplace_back(glm::dvec3(transform.world * p));
  }

  if (const int a = find_attribute(primitive, "NORMAL"); a >= 0) {
    const std::vector<float> normals =
        read_floats(model, a, TINYGLTF_TYPE_VEC3, false, field + ".NORMAL");
    check_count(normals, 3, n, field + ".NORMAL");
    mesh.normals.reserve(n);
    for (std::size_t i = 0; i < n; ++i) {
      const glm::dvec3 v(normals[3 * i], normals[3 * i + 1], normals[3 * i + 2]);
      mesh.normals.emplace_back(normalized_or_same(transform.normal_matrix * v));
    }
  }
  if (const int a = find_attribute(primitive, "TANGENT"); a >= 0) {
    const std::vector<float> tangents =
        read_floats(model, a, TINYGLTF_TYPE_VEC4, false, field + ".TANGENT");
    check_count(tangents, 4, n, field + ".TANGENT");
    mesh.tangents.reserve(n);
    const float sign = transform.mirrors ? -1.0f : 1.0f;
    for (std::size_t i = 0; i < n; ++i) {
      const glm::dvec3 t(tangents[4 * i], tangents[4 * i + 1], tangents[4 * i + 2]);
      const glm::vec3 xyz(normalized_or_same(transform.linear * t));
      mesh.tangents.emplace_back(xyz, sign * tangents[4 * i + 3]);
    }
    part.has_tangents = true;
  }
  if (const int a = find_attribute(primitive, "TEXCOORD_0"); a >= 0) {
    const std::vector<float> texcoords =
        read_floats(model, a, TINYGLTF_TYPE_VEC2, true, field + ".TEXCOORD_0");
    check_count(texcoords, 2, n, field + ".TEXCOORD_0");
    mesh.texcoords.reserve(n);
    for (std::size_t i = 0; i < n; ++i) {
      mesh.texcoords.emplace_back(texcoords[2 * i], texcoords[2 * i + 1]);
    }
    part.has_texcoords = true;
  }

  if (primitive.indices >= 0) {
    mesh.indices = read_indices(model, primitive.indices, field + ".indices");
  } else {  // non-indexed: vertices 0, 1, 2, ... in order
    mesh.indices.resize(n);
    for (std::size_t i = 0; i < n; ++i) mesh.indices[i] = static_cast<std::uint32_t>(i);
  }
  if (mesh.indices.size() % 3 != 0) {
    throw_format(field + ".indices", "has " + std::to_string(mesh.indices.size()) +
                                         " entries, not a multiple of 3 (TRIANGLES)");
  }
  for (std::size_t i = 0; i < mesh.indices.size(); ++i) {
    if (mesh.indices[i] >= n) {
      const std::string index_field = indexed(field + ".indices", i);
      throw Error(ErrorCode::kInvalidMesh, index_field,
                  index_field + " = " + std::to_string(mesh.indices[i]) +
                      " is out of range (vertex count " + std::to_string(n) + ")");
    }
  }
  if (transform.mirrors) {  // keep triangles counter-clockwise seen from outside
    for (std::size_t t = 0; t < mesh.indices.size(); t += 3) {
      std::swap(mesh.indices[t + 1], mesh.indices[t + 2]);
    }
  }
  if (mesh.normals.empty()) compute_vertex_normals(mesh);
  return part;
}

glm::dmat4 local_matrix(const tinygltf::Node& node, const std::string& field) {
  if (!node.matrix.empty()) {
    if (node.matrix.size() != 16) throw_format(field + ".matrix", "must have 16 numbers");
    return glm::make_mat4(node.matrix.data());  // both column-major
  }
  if (!node.translation.empty() && node.translation.size() != 3) {
    throw_format(field + ".translation", "must have 3 numbers");
  }
  if (!node.rotation.empty() && node.rotation.size() != 4) {
    throw_format(field + ".rotation", "must have 4 numbers");
  }
  if (!node.scale.empty() && node.scale.size() != 3) {
    throw_format(field + ".scale", "must have 3 numbers");
  }
  glm::dmat4 m(1.0);  // T * R * S
  if (!node.translation.empty()) m = glm::translate(m, glm::make_vec3(node.translation.data()));
  if (!node.rotation.empty()) {
    const std::vector<double>& r = node.rotation;  // glTF: x, y, z, w
    m *= glm::mat4_cast(glm::normalize(glm::dquat(r[3], r[0], r[1], r[2])));
  }
  if (!node.scale.empty()) m = glm::scale(m, glm::make_vec3(node.scale.data()));
  return m;
}

// Depth-first flattening of the node hierarchy into parts, in traversal order.
class SceneFlattener {
 public:
  explicit SceneFlattener(const tinygltf::Model& model)
      : model_(model), on_path_(model.nodes.size(), false) {}

  void visit(int node_index, const glm::dmat4& parent, const std::string& referrer) {
    if (node_index < 0 || static_cast<std::size_t>(node_index) >= model_.nodes.size()) {
      throw_format(referrer, "node " + std::to_string(node_index) + " does not exist (" +
                                 std::to_string(model_.nodes.size()) + " nodes)");
    }
    const std::size_t index = static_cast<std::size_t>(node_index);
    const std::string field = indexed("nodes", index);
    if (on_path_[index]) throw_format(field, "is its own ancestor (cycle in children)");
    on_path_[index] = true;
    const tinygltf::Node& node = model_.nodes[index];
    const glm::dmat4 world = parent * local_matrix(node, field);
    if (node.mesh >= 0) add_mesh(node.mesh, Transform(world), field + ".mesh");
    for (const int child : node.children) visit(child, world, field + ".children");
    on_path_[index] = false;
  }

  std::vector<Part>& parts() { return parts_; }

 private:
  void add_mesh(int mesh_index, const Transform& transform, const std::string& referrer) {
    if (static_cast<std::size_t>(mesh_index) >= model_.meshes.size()) {
      throw_format(referrer, "mesh " + std::to_string(mesh_index) + " does not exist (" +
                                 std::to_string(model_.meshes.size()) + " meshes)");
    }
    const tinygltf::Mesh& mesh = model_.meshes[static_cast<std::size_t>(mesh_index)];
    const std::string mesh_field = indexed("meshes", static_cast<std::size_t>(mesh_index));
    for (std::size_t p = 0; p < mesh.primitives.size(); ++p) {
      const std::string field = indexed(mesh_field + ".primitives", p);
      try {
        parts_.push_back(read_primitive(model_, mesh.primitives[p], transform, field));
        parts_.back().group =
            (mesh.name.empty() ? std::to_string(mesh_index) : mesh.name) + "/" + std::to_string(p);
      } catch (const Error& e) {
        // Messages start with the field ("meshes[0].primitives[1]..."): add the
        // mesh's name after "meshes[0]"; the field itself stays as it is.
        std::string message = e.what();
        if (!mesh.name.empty() && message.rfind(mesh_field, 0) == 0) {
          message.insert(mesh_field.size(), " ('" + mesh.name + "')");
        }
        throw Error(e.code(), e.field(), message);
      }
    }
  }

  const tinygltf::Model& model_;
  std::vector<bool> on_path_;
  std::vector<Part> parts_;
};

// The scene's root nodes: the default scene's, else scene 0's, else (no scenes)
// every node that is no node's child.
std::vector<int> root_nodes(const tinygltf::Model& model) {
  if (!model.scenes.empty()) {
    const int scene = model.defaultScene >= 0 ? model.defaultScene : 0;
    if (static_cast<std::size_t>(scene) >= model.scenes.size()) {
      throw_format("scene", std::to_string(scene) + " does not exist (" +
                                std::to_string(model.scenes.size()) + " scenes)");
    }
    return model.scenes[static_cast<std::size_t>(scene)].nodes;
  }
  std::vector<bool> is_child(model.nodes.size(), false);
  for (const tinygltf::Node& node : model.nodes) {
    for (const int child : node.children) {
      if (child >= 0 && static_cast<std::size_t>(child) < is_child.size()) {
        is_child[static_cast<std::size_t>(child)] = true;
      }
    }
  }
  std::vector<int> roots;
  for (std::size_t i = 0; i < model.nodes.size(); ++i) {
    if (!is_child[i]) roots.push_back(static_cast<int>(i));
  }
  return roots;
}

// Concatenates the parts. Tangents survive only if every part has them; texcoords
// if any part has them (the others get (0, 0)). Each part with triangles becomes a
// FaceGroup (a mesh placed by several nodes gives several groups of the same name).
Mesh concatenate(const std::vector<Part>& parts) {
  const bool all_tangents =
      std::all_of(parts.begin(), parts.end(), [](const Part& p) { return p.has_tangents; });
  const bool any_texcoords =
      std::any_of(parts.begin(), parts.end(), [](const Part& p) { return p.has_texcoords; });
  Mesh out;
  for (const Part& part : parts) {
    const Mesh& m = part.mesh;
    const std::size_t base = out.positions.size();
    if (base + m.positions.size() > UINT32_MAX) {
      throw_format("meshes", "more than 2^32 vertices in the scene");
    }
    out.positions.insert(out.positions.end(), m.positions.begin(), m.positions.end());
    out.normals.insert(out.normals.end(), m.normals.begin(), m.normals.end());
    if (all_tangents) out.tangents.insert(out.tangents.end(), m.tangents.begin(), m.tangents.end());
    if (any_texcoords) {
      if (part.has_texcoords) {
        out.texcoords.insert(out.texcoords.end(), m.texcoords.begin(), m.texcoords.end());
      } else {
        out.texcoords.resize(out.texcoords.size() + m.positions.size(), glm::vec2(0.0f));
      }
    }
    const std::size_t first_triangle = out.triangle_count();
    for (const std::uint32_t index : m.indices) {
      out.indices.push_back(static_cast<std::uint32_t>(base) + index);
    }
    if (m.triangle_count() > 0) {
      out.groups.push_back(FaceGroup{part.group, first_triangle, m.triangle_count()});
    }
  }
  return out;
}

// ---------------------------------------------------------------------------------
// Writing

// Appends `bytes` to the buffer as a new bufferView (4-byte aligned); returns its index.
int add_buffer_view(tinygltf::Model& model, const void* bytes, std::size_t size, int target) {
  std::vector<unsigned char>& data = model.buffers[0].data;
  data.resize((data.size() + 3) / 4 * 4, 0);
  tinygltf::BufferView view;
  view.buffer = 0;
  view.byteOffset = data.size();
  view.byteLength = size;
  view.target = target;
  const unsigned char* begin = static_cast<const unsigned char*>(bytes);
  data.insert(data.end(), begin, begin + size);
  model.bufferViews.push_back(view);
  return static_cast<int>(model.bufferViews.size() - 1);
}

// Adds a tightly packed float accessor over `values` (count elements of `type`).
template <typename Vec>
int add_float_accessor(tinygltf::Model& model, const std::vector<Vec>& values, int type) {
  tinygltf::Accessor accessor;
  accessor.bufferView = add_buffer_view(model, values.data(), values.size() * sizeof(Vec),
                                        TINYGLTF_TARGET_ARRAY_BUFFER);
  accessor.byteOffset = 0;
  accessor.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
  accessor.count = values.size();
  accessor.type = type;
  model.accessors.push_back(accessor);
  return static_cast<int>(model.accessors.size() - 1);
}

tinygltf::Model build_model(const Mesh& mesh) {
  static_assert(sizeof(glm::vec3) == 12 && sizeof(glm::vec4) == 16 && sizeof(glm::vec2) == 8,
                "glm vectors must be tightly packed floats");
  if (mesh.indices.empty()) {
    throw Error(ErrorCode::kInvalidMesh, "indices",
                "indices is empty: a glTF TRIANGLES primitive needs at least one triangle");
  }
  tinygltf::Model model;
  model.asset.version = "2.0";
  model.asset.generator = "FinFlex";
  model.buffers.emplace_back();

  tinygltf::Primitive primitive;
  primitive.mode = TINYGLTF_MODE_TRIANGLES;
  const int position = add_float_accessor(model, mesh.positions, TINYGLTF_TYPE_VEC3);
  glm::vec3 lo = mesh.positions[0], hi = mesh.positions[0];
  for (const glm::vec3& p : mesh.positions) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  model.accessors[static_cast<std::size_t>(position)].minValues = {lo.x, lo.y, lo.z};
  model.accessors[static_cast<std::size_t>(position)].maxValues = {hi.x, hi.y, hi.z};
  primitive.attributes["POSITION"] = position;
  primitive.attributes["NORMAL"] = add_float_accessor(model, mesh.normals, TINYGLTF_TYPE_VEC3);
  if (mesh.has_tangents()) {
    primitive.attributes["TANGENT"] = add_float_accessor(model, mesh.tangents, TINYGLTF_TYPE_VEC4);
  }
  if (!mesh.texcoords.empty()) {
    primitive.attributes["TEXCOORD_0"] =
        add_float_accessor(model, mesh.texcoords, TINYGLTF_TYPE_VEC2);
  }

  tinygltf::Accessor indices;
  indices.bufferView =
      add_buffer_view(model, mesh.indices.data(), mesh.indices.size() * sizeof(std::uint32_t),
                      TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
  indices.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
  indices.count = mesh.indices.size();
  indices.type = TINYGLTF_TYPE_SCALAR;
  model.accessors.push_back(indices);
  primitive.indices = static_cast<int>(model.accessors.size() - 1);

  tinygltf::Mesh gltf_mesh;
  gltf_mesh.primitives.push_back(primitive);
  model.meshes.push_back(gltf_mesh);
  tinygltf::Node node;
  node.mesh = 0;
  model.nodes.push_back(node);
  tinygltf::Scene scene;
  scene.nodes.push_back(0);
  model.scenes.push_back(scene);
  model.defaultScene = 0;
  return model;
}

}  // namespace

Mesh read_gltf(std::string_view bytes, const std::string& base_dir) {
  const LoadedGltf gltf = load_gltf_model(bytes, base_dir);
  const tinygltf::Model& model = gltf.model;
  SceneFlattener flattener(model);
  for (const int root : root_nodes(model)) flattener.visit(root, glm::dmat4(1.0), "scene");
  if (flattener.parts().empty()) {
    throw Error(ErrorCode::kFormat, "meshes", "the scene has no mesh primitives");
  }
  return concatenate(flattener.parts());
}

void write_gltf(std::ostream& out, MeshFormat format, const Mesh& mesh) {
  const tinygltf::Model model = build_model(mesh);
  tinygltf::TinyGLTF writer;
  const bool binary = format == MeshFormat::kGlb;
  // .gltf: the buffer is embedded as a base64 data URI, so the file stands alone.
  if (!writer.WriteGltfSceneToStream(&model, out, /*prettyPrint=*/!binary, binary)) {
    throw Error(ErrorCode::kIo, "path", "tinygltf could not serialize the mesh");
  }
}

}  // namespace finflex::io
