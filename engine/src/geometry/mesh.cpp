// Mesh validation and normals (see finflex/mesh.hpp for the contracts).
#include "finflex/mesh.hpp"

#include <cmath>
#include <string>

#include "finflex/error.hpp"

namespace finflex {
namespace {

const char* const kAxisNames[] = {"x", "y", "z", "w"};
const char* const kTexAxisNames[] = {"u", "v"};

std::string element_name(const char* array, std::size_t index) {
  return std::string(array) + "[" + std::to_string(index) + "]";
}

// "NaN", "+inf" or "-inf" for a non-finite value.
std::string non_finite_name(double value) {
  if (std::isnan(value)) return "NaN";
  return value > 0 ? "+inf" : "-inf";
}

[[noreturn]] void throw_invalid(const std::string& field, const std::string& message) {
  throw Error(ErrorCode::kInvalidMesh, field, message);
}

// Throws unless `attribute` is empty or holds one entry per vertex.
template <typename T>
void check_attribute_length(const char* name, const std::vector<T>& attribute,
                            std::size_t vertex_count) {
  if (attribute.empty() || attribute.size() == vertex_count) return;
  throw_invalid(name, std::string(name) + " has " + std::to_string(attribute.size()) +
                          " entries, expected 0 or " + std::to_string(vertex_count) +
                          " (one per vertex)");
}

// Throws for the first non-finite component of the first non-finite element.
// `axis_names` names the components in messages (x y z w, or u v).
template <typename Vec>
void check_finite(const char* name, const std::vector<Vec>& values, const char* const* axis_names) {
  for (std::size_t i = 0; i < values.size(); ++i) {
    for (int c = 0; c < Vec::length(); ++c) {
      const double value = static_cast<double>(values[i][c]);
      if (std::isfinite(value)) continue;
      const std::string field = element_name(name, i) + "." + axis_names[c];
      throw_invalid(field, field + " is " + non_finite_name(value));
    }
  }
}

void check_indices(const std::vector<std::uint32_t>& indices, std::size_t vertex_count) {
  if (indices.size() % 3 != 0) {
    throw_invalid("indices", "indices has " + std::to_string(indices.size()) +
                                 " entries, not a multiple of 3 (triangles)");
  }
  for (std::size_t i = 0; i < indices.size(); ++i) {
    if (indices[i] < vertex_count) continue;
    const std::string field = element_name("indices", i);
    throw_invalid(field, field + " = " + std::to_string(indices[i]) +
                             " is out of range (vertex count " + std::to_string(vertex_count) +
                             ")");
  }
}

void check_nonzero_normals(const std::vector<glm::vec3>& normals) {
  for (std::size_t i = 0; i < normals.size(); ++i) {
    if (normals[i] != glm::vec3(0.0f)) continue;
    const std::string field = element_name("normals", i);
    throw_invalid(field, field + " = (0, 0, 0) has zero length");
  }
}

// Twice the area times the unit normal of triangle (a, b, c), in double.
glm::dvec3 weighted_face_normal(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c) {
  const glm::dvec3 da(a);
  return glm::cross(glm::dvec3(b) - da, glm::dvec3(c) - da);
}

}  // namespace

void validate_mesh(const Mesh& mesh) {
  const std::size_t n = mesh.vertex_count();
  if (n == 0) throw_invalid("positions", "mesh has no vertices (positions is empty)");
  check_attribute_length("normals", mesh.normals, n);
  check_attribute_length("tangents", mesh.tangents, n);
  check_attribute_length("texcoords", mesh.texcoords, n);
  check_indices(mesh.indices, n);
  check_finite("positions", mesh.positions, kAxisNames);
  check_finite("normals", mesh.normals, kAxisNames);
  check_finite("tangents", mesh.tangents, kAxisNames);
  check_finite("texcoords", mesh.texcoords, kTexAxisNames);
  check_nonzero_normals(mesh.normals);
}

void compute_vertex_normals(Mesh& mesh) {
  check_indices(mesh.indices, mesh.vertex_count());
  std::vector<glm::dvec3> sums(mesh.vertex_count(), glm::dvec3(0.0));
  const auto& p = mesh.positions;
  for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
    const std::uint32_t i0 = mesh.indices[t], i1 = mesh.indices[t + 1], i2 = mesh.indices[t + 2];
    const glm::dvec3 weighted = weighted_face_normal(p[i0], p[i1], p[i2]);
    sums[i0] += weighted;
    sums[i1] += weighted;
    sums[i2] += weighted;
  }
  mesh.normals.resize(mesh.vertex_count());
  for (std::size_t v = 0; v < sums.size(); ++v) {
    const double length = glm::length(sums[v]);
    mesh.normals[v] = length > 0.0 && std::isfinite(length) ? glm::vec3(sums[v] / length)
                                                            : glm::vec3(0.0f, 0.0f, 1.0f);
  }
}

std::vector<glm::dvec3> face_normals(const std::vector<glm::vec3>& positions,
                                     const std::vector<std::uint32_t>& indices) {
  check_indices(indices, positions.size());
  std::vector<glm::dvec3> normals;
  normals.reserve(indices.size() / 3);
  for (std::size_t t = 0; t + 2 < indices.size(); t += 3) {
    const glm::dvec3 weighted = weighted_face_normal(
        positions[indices[t]], positions[indices[t + 1]], positions[indices[t + 2]]);
    const double length = glm::length(weighted);
    normals.push_back(length > 0.0 && std::isfinite(length) ? weighted / length : glm::dvec3(0.0));
  }
  return normals;
}

}  // namespace finflex
