// glTF 2.0 (.gltf) and GLB (.glb) reading: the scene flattened into one Mesh.
//
// Every node that carries a mesh adds the TRIANGLES primitives of that mesh, in
// depth-first node order (scene_nodes), transformed to world space; each primitive
// becomes a FaceGroup named "<mesh name or index>/<primitive index>". The work is
// bounded by the input's size: at most kPlacedElementsPerInputByte vertices, indices
// and group-name bytes per byte of input, however often nodes instance a mesh.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "finflex/error.hpp"
#include "io/formats.hpp"
#include "io/gltf.hpp"
#include "io/text.hpp"

namespace finflex::io {
namespace {

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

bool is_finite(const glm::vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// Unit vector along v, or v itself if it has zero length.
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
  throw_gltf_format(field, "has " + std::to_string(values.size() / components) +
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

Part read_primitive(const LoadedGltf& gltf, const tinygltf::Primitive& primitive,
                    const Transform& transform, const std::string& field) {
  if (primitive.mode != TINYGLTF_MODE_TRIANGLES) {
    throw_gltf_format(field, std::string("mode ") + std::to_string(primitive.mode) + " (" +
                                 mode_name(primitive.mode) + ") is not supported (only TRIANGLES)");
  }
  const int position_accessor = find_attribute(primitive, "POSITION");
  if (position_accessor < 0) throw_gltf_format(field, "has no POSITION attribute");
  const std::vector<float> positions =
      read_floats(gltf, position_accessor, TINYGLTF_TYPE_VEC3, false, field + ".POSITION");
  const std::size_t n = positions.size() / 3;

  Part part;
  Mesh& mesh = part.mesh;
  mesh.positions.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    const glm::dvec4 p(positions[3 * i], positions[3 * i + 1], positions[3 * i + 2], 1.0);
    const glm::vec3 placed(glm::dvec3(transform.world * p));
    if (!is_finite(placed)) {
      throw Error(ErrorCode::kInvalidMesh, field + ".POSITION",
                  indexed(field + ".POSITION", i) +
                      ": the node's transform takes it outside the float range");
    }
    mesh.positions.push_back(placed);
  }

  if (const int a = find_attribute(primitive, "NORMAL"); a >= 0) {
    const std::vector<float> normals =
        read_floats(gltf, a, TINYGLTF_TYPE_VEC3, false, field + ".NORMAL");
    check_count(normals, 3, n, field + ".NORMAL");
    mesh.normals.reserve(n);
    for (std::size_t i = 0; i < n; ++i) {
      const glm::dvec3 v(normals[3 * i], normals[3 * i + 1], normals[3 * i + 2]);
      const glm::vec3 unit(normalized_or_same(transform.normal_matrix * v));
      if (!is_finite(unit) || unit == glm::vec3(0.0f)) {
        const std::string element = indexed(field + ".NORMAL", i);
        throw Error(
            ErrorCode::kInvalidMesh, element,
            element + (unit == glm::vec3(0.0f) ? " has zero length"
                                               : ": the node's transform makes it non-finite"));
      }
      mesh.normals.push_back(unit);
    }
  }
  if (const int a = find_attribute(primitive, "TANGENT"); a >= 0) {
    const std::vector<float> tangents =
        read_floats(gltf, a, TINYGLTF_TYPE_VEC4, false, field + ".TANGENT");
    check_count(tangents, 4, n, field + ".TANGENT");
    mesh.tangents.reserve(n);
    const float sign = transform.mirrors ? -1.0f : 1.0f;
    for (std::size_t i = 0; i < n; ++i) {
      const glm::dvec3 t(tangents[4 * i], tangents[4 * i + 1], tangents[4 * i + 2]);
      const glm::vec3 xyz(normalized_or_same(transform.linear * t));
      if (!is_finite(xyz)) {
        const std::string element = indexed(field + ".TANGENT", i);
        throw Error(ErrorCode::kInvalidMesh, element,
                    element + ": the node's transform makes it non-finite");
      }
      mesh.tangents.emplace_back(xyz, sign * tangents[4 * i + 3]);
    }
    part.has_tangents = true;
  }
  if (const int a = find_attribute(primitive, "TEXCOORD_0"); a >= 0) {
    const std::vector<float> texcoords =
        read_floats(gltf, a, TINYGLTF_TYPE_VEC2, true, field + ".TEXCOORD_0");
    check_count(texcoords, 2, n, field + ".TEXCOORD_0");
    mesh.texcoords.reserve(n);
    for (std::size_t i = 0; i < n; ++i) {
      mesh.texcoords.emplace_back(texcoords[2 * i], texcoords[2 * i + 1]);
    }
    part.has_texcoords = true;
  }

  if (primitive.indices >= 0) {
    mesh.indices = read_indices(gltf, primitive.indices, field + ".indices");
  } else {  // non-indexed: vertices 0, 1, 2, ... in order
    mesh.indices.resize(n);
    for (std::size_t i = 0; i < n; ++i) mesh.indices[i] = static_cast<std::uint32_t>(i);
  }
  if (mesh.indices.size() % 3 != 0) {
    throw_gltf_format(field + ".indices", "has " + std::to_string(mesh.indices.size()) +
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
    if (node.matrix.size() != 16) throw_gltf_format(field + ".matrix", "must have 16 numbers");
    return glm::make_mat4(node.matrix.data());  // both column-major
  }
  if (!node.translation.empty() && node.translation.size() != 3) {
    throw_gltf_format(field + ".translation", "must have 3 numbers");
  }
  if (!node.rotation.empty() && node.rotation.size() != 4) {
    throw_gltf_format(field + ".rotation", "must have 4 numbers");
  }
  if (!node.scale.empty() && node.scale.size() != 3) {
    throw_gltf_format(field + ".scale", "must have 3 numbers");
  }
  glm::dmat4 m(1.0);  // T * R * S
  if (!node.translation.empty()) m = glm::translate(m, glm::make_vec3(node.translation.data()));
  if (!node.rotation.empty()) {
    const std::vector<double>& r = node.rotation;  // glTF: x, y, z, w
    const glm::dquat q(r[3], r[0], r[1], r[2]);
    // glm would turn a zero quaternion into the identity without a word.
    if (!(glm::length(q) > 0.0)) {
      throw_gltf_format(field + ".rotation", "is not a rotation (a quaternion of zero length)");
    }
    m *= glm::mat4_cast(glm::normalize(q));
  }
  if (!node.scale.empty()) m = glm::scale(m, glm::make_vec3(node.scale.data()));
  return m;
}

// Throws unless `world`, the transform of nodes[node] that places a mesh, is finite
// and invertible (normals go through its inverse transpose).
void check_transform(const glm::dmat4& world, std::size_t node) {
  const std::string field = indexed("nodes", node);
  for (int c = 0; c < 4; ++c) {
    for (int r = 0; r < 4; ++r) {
      if (!std::isfinite(world[c][r])) {
        throw_gltf_format(field, "its transform (with its ancestors') is not finite");
      }
    }
  }
  if (glm::determinant(glm::dmat3(world)) == 0.0) {
    throw_gltf_format(field, "its transform (with its ancestors') is singular (determinant 0)");
  }
}

// Flattens the scene into parts, node by node in scene_nodes() order.
class SceneFlattener {
 public:
  explicit SceneFlattener(const LoadedGltf& gltf)
      : gltf_(gltf), budget_(gltf.input_bytes * kPlacedElementsPerInputByte) {}

  void flatten() {
    const tinygltf::Model& model = gltf_.model;
    const std::vector<PlacedNode> nodes = scene_nodes(model);
    std::vector<glm::dmat4> world(nodes.size());
    for (std::size_t i = 0; i < nodes.size(); ++i) {
      const tinygltf::Node& node = model.nodes[nodes[i].node];
      const glm::dmat4 parent =
          nodes[i].parent < 0 ? glm::dmat4(1.0) : world[static_cast<std::size_t>(nodes[i].parent)];
      world[i] = parent * local_matrix(node, indexed("nodes", nodes[i].node));
      if (node.mesh >= 0) {
        check_transform(world[i], nodes[i].node);
        add_mesh(node.mesh, Transform(world[i]), nodes[i].node);
      }
    }
  }

  std::vector<Part>& parts() { return parts_; }

 private:
  void add_mesh(int mesh_index, const Transform& transform, std::size_t node) {
    const tinygltf::Model& model = gltf_.model;
    if (static_cast<std::size_t>(mesh_index) >= model.meshes.size()) {
      throw_gltf_format(indexed("nodes", node) + ".mesh",
                        "mesh " + std::to_string(mesh_index) + " does not exist (" +
                            std::to_string(model.meshes.size()) + " meshes)");
    }
    const tinygltf::Mesh& mesh = model.meshes[static_cast<std::size_t>(mesh_index)];
    const std::string mesh_field = indexed("meshes", static_cast<std::size_t>(mesh_index));
    for (std::size_t p = 0; p < mesh.primitives.size(); ++p) {
      const std::string field = indexed(mesh_field + ".primitives", p);
      try {
        parts_.push_back(read_primitive(gltf_, mesh.primitives[p], transform, field));
      } catch (const Error& e) {
        if (mesh.name.empty()) throw;
        // The mesh's name helps find it: "meshes[0].primitives[1]: ...; mesh 'fin'".
        throw Error(e.code(), e.field(), std::string(e.what()) + "; mesh " + shown(mesh.name));
      }
      Part& part = parts_.back();
      part.group =
          (mesh.name.empty() ? std::to_string(mesh_index) : mesh.name) + "/" + std::to_string(p);
      placed_ += part.mesh.positions.size() + part.mesh.indices.size() + part.group.size();
      if (placed_ > budget_) {
        throw_gltf_format(indexed("nodes", node),
                          "placing " + mesh_field + " here brings the scene to more than " +
                              std::to_string(budget_) +
                              " vertices, indices and group-name bytes (" +
                              std::to_string(kPlacedElementsPerInputByte) + " per byte of the " +
                              std::to_string(gltf_.input_bytes) +
                              " bytes of input): too many instances of its meshes");
      }
    }
  }

  const LoadedGltf& gltf_;
  std::uint64_t budget_;
  std::uint64_t placed_ = 0;
  std::vector<Part> parts_;
};

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
      throw_gltf_format("meshes", "more than 2^32 vertices in the scene");
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

}  // namespace

Mesh read_gltf(std::string_view bytes, const std::string& base_dir) {
  const LoadedGltf gltf = load_gltf_model(bytes, base_dir);
  SceneFlattener flattener(gltf);
  flattener.flatten();
  if (flattener.parts().empty()) {
    throw Error(ErrorCode::kFormat, "meshes", "meshes: the scene has no mesh primitives");
  }
  return concatenate(flattener.parts());
}

}  // namespace finflex::io
