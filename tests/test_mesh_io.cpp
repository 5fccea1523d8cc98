// The mesh module: validation, normals, loading the bundled fish, round trips through
// every format, crafted glTF scenes, and the errors (code, field, untouched files).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <map>
#include <sstream>
#include <string>
#include <thread>
#include <tuple>
#include <vector>

#include "finflex/error.hpp"
#include "finflex/mesh.hpp"
#include "finflex/mesh_io.hpp"
#include "support/test_support.hpp"
#include "support/throws_error.hpp"

namespace finflex {
namespace {

using test::ThrowsError;

namespace fs = std::filesystem;
using test::data_path;
using test::temp_path;

// ---------------------------------------------------------------------------------
// Helpers

void write_file(const std::string& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary);
  out << bytes;
  ASSERT_TRUE(out.good()) << path;
}

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream bytes;
  bytes << in.rdbuf();
  return bytes.str();
}

std::vector<std::string> folder_entries(const fs::path& folder) {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(folder)) {
    names.push_back(entry.path().filename().string());
  }
  std::sort(names.begin(), names.end());
  return names;
}

template <typename T>
void append_bytes(std::string& out, const T& value) {
  out.append(reinterpret_cast<const char*>(&value), sizeof value);
}

// The "v", "vt" and "vn" lines and the polygons of the "f" lines (0-based) of an OBJ
// file.
struct ObjText {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec2> texcoords;
  std::vector<glm::vec3> normals;
  std::vector<std::vector<std::uint32_t>> faces;           // vertex per corner
  std::vector<std::vector<std::uint32_t>> face_texcoords;  // "vt" per corner, if given
  std::vector<std::vector<std::uint32_t>> face_normals;    // "vn" per corner, if given
};

ObjText parse_obj(const std::string& path) {
  ObjText obj;
  std::ifstream in(path);
  std::string line;
  const auto number = [](const std::string& word) { return std::strtof(word.c_str(), nullptr); };
  while (std::getline(in, line)) {
    std::istringstream words(line);
    std::string key, x, y, z;
    words >> key;
    if (key == "v") {
      words >> x >> y >> z;
      obj.positions.emplace_back(number(x), number(y), number(z));
    } else if (key == "vt") {
      words >> x >> y;
      obj.texcoords.emplace_back(number(x), number(y));
    } else if (key == "vn") {
      words >> x >> y >> z;
      obj.normals.emplace_back(number(x), number(y), number(z));
    } else if (key == "f") {
      std::vector<std::uint32_t> face, texcoords, normals;
      std::string corner;
      while (words >> corner) {  // v, v/vt, v//vn or v/vt/vn
        std::istringstream parts(corner);
        std::string v, vt, vn;
        std::getline(parts, v, '/');
        std::getline(parts, vt, '/');
        std::getline(parts, vn, '/');
        face.push_back(static_cast<std::uint32_t>(std::stoul(v) - 1));
        if (!vt.empty()) texcoords.push_back(static_cast<std::uint32_t>(std::stoul(vt) - 1));
        if (!vn.empty()) normals.push_back(static_cast<std::uint32_t>(std::stoul(vn) - 1));
      }
      obj.faces.push_back(face);
      obj.face_texcoords.push_back(texcoords);
      obj.face_normals.push_back(normals);
    }
  }
  return obj;
}

struct Box {
  glm::vec3 lo{std::numeric_limits<float>::max()};
  glm::vec3 hi{std::numeric_limits<float>::lowest()};
};

Box bounding_box(const std::vector<glm::vec3>& points) {
  Box box;
  for (const glm::vec3& p : points) {
    box.lo = glm::min(box.lo, p);
    box.hi = glm::max(box.hi, p);
  }
  return box;
}

// Area-weighted vertex normals built from face_normals(), independently of
// compute_vertex_normals().
std::vector<glm::dvec3> normals_from_faces(const Mesh& mesh) {
  const std::vector<glm::dvec3> faces = face_normals(mesh.positions, mesh.indices);
  std::vector<glm::dvec3> sums(mesh.vertex_count(), glm::dvec3(0.0));
  for (std::size_t t = 0; t < faces.size(); ++t) {
    const glm::dvec3 a(mesh.positions[mesh.indices[3 * t]]);
    const glm::dvec3 b(mesh.positions[mesh.indices[3 * t + 1]]);
    const glm::dvec3 c(mesh.positions[mesh.indices[3 * t + 2]]);
    const double area = 0.5 * glm::length(glm::cross(b - a, c - a));
    for (int k = 0; k < 3; ++k) {
      sums[mesh.indices[3 * t + static_cast<std::size_t>(k)]] += area * faces[t];
    }
  }
  for (glm::dvec3& n : sums) n = glm::length(n) > 0.0 ? glm::normalize(n) : glm::dvec3(0, 0, 1);
  return sums;
}

void expect_unit_normals(const Mesh& mesh) {
  ASSERT_EQ(mesh.normals.size(), mesh.vertex_count());
  for (std::size_t v = 0; v < mesh.normals.size(); ++v) {
    ASSERT_NEAR(glm::length(mesh.normals[v]), 1.0f, 1e-5f) << "normals[" << v << "]";
  }
}

void expect_near(const std::vector<glm::vec3>& actual, const std::vector<glm::vec3>& expected,
                 float tolerance, const char* what) {
  ASSERT_EQ(actual.size(), expected.size()) << what;
  for (std::size_t i = 0; i < actual.size(); ++i) {
    for (int c = 0; c < 3; ++c) {
      ASSERT_NEAR(actual[i][c], expected[i][c], tolerance) << what << "[" << i << "][" << c << "]";
    }
  }
}

// The low-resolution Blub with texcoords and tangents added, so that every
// attribute goes through the writers.
Mesh decorated_fish() {
  Mesh mesh = load_mesh(data_path("blub/fish_low_resolution.obj"));
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
    const glm::vec3& p = mesh.positions[v];
    mesh.texcoords.emplace_back(0.5f + p.x, 0.5f + p.y);
    glm::vec3 t = glm::cross(mesh.normals[v], glm::vec3(0.0f, 1.0f, 0.0f));
    if (glm::length(t) < 1e-3f) t = glm::vec3(1.0f, 0.0f, 0.0f);
    mesh.tangents.emplace_back(glm::normalize(t), v % 2 == 0 ? 1.0f : -1.0f);
  }
  return mesh;
}

// A unit square in the plane z = 0 made of two triangles, without normals.
Mesh flat_square() {
  Mesh mesh;
  mesh.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  mesh.indices = {0, 1, 2, 0, 2, 3};
  return mesh;
}

// ---------------------------------------------------------------------------------
// validate_mesh, compute_vertex_normals, face_normals

TEST(ValidateMesh, AcceptsTheDecoratedFish) { EXPECT_NO_THROW(validate_mesh(decorated_fish())); }

TEST(ValidateMesh, NamesTheFirstBadFieldAndValue) {
  const Mesh good = decorated_fish();
  const auto check = [](const Mesh& mesh) { return [mesh] { validate_mesh(mesh); }; };

  EXPECT_TRUE(ThrowsError(check(Mesh{}), ErrorCode::kInvalidMesh, "positions", "no vertices"));
  Mesh m = good;
  m.normals.pop_back();
  EXPECT_TRUE(
      ThrowsError(check(m), ErrorCode::kInvalidMesh, "normals", "944 entries, expected 0 or 945"));
  m = good;
  m.tangents.push_back(glm::vec4(1, 0, 0, 1));
  EXPECT_TRUE(ThrowsError(check(m), ErrorCode::kInvalidMesh, "tangents", "946 entries"));
  m = good;
  m.texcoords.resize(3);
  EXPECT_TRUE(ThrowsError(check(m), ErrorCode::kInvalidMesh, "texcoords", "3 entries"));
  m = good;
  m.indices.pop_back();
  EXPECT_TRUE(ThrowsError(check(m), ErrorCode::kInvalidMesh, "indices", "not a multiple of 3"));
  m = good;
  m.indices[7] = 99999;
  EXPECT_TRUE(ThrowsError(check(m), ErrorCode::kInvalidMesh, "indices[7]",
                          "indices[7] = 99999 is out of range (vertex count 945)"));
  m = good;
  m.positions[12].y = std::numeric_limits<float>::quiet_NaN();
  EXPECT_TRUE(
      ThrowsError(check(m), ErrorCode::kInvalidMesh, "positions[12].y", "positions[12].y is NaN"));
  m = good;
  m.normals[5].z = -std::numeric_limits<float>::infinity();
  EXPECT_TRUE(ThrowsError(check(m), ErrorCode::kInvalidMesh, "normals[5].z", "is -inf"));
  m = good;
  m.normals[3] = glm::vec3(0.0f);
  EXPECT_TRUE(ThrowsError(check(m), ErrorCode::kInvalidMesh, "normals[3]", "zero length"));
  m = good;
  m.tangents[2].w = std::numeric_limits<float>::quiet_NaN();
  EXPECT_TRUE(ThrowsError(check(m), ErrorCode::kInvalidMesh, "tangents[2].w", "is NaN"));
  m = good;
  m.texcoords[1].y = std::numeric_limits<float>::infinity();
  EXPECT_TRUE(ThrowsError(check(m), ErrorCode::kInvalidMesh, "texcoords[1].v", "is +inf"));
}

TEST(ValidateMesh, AcceptsAPointCloudAndOptionalAttributesLeftEmpty) {
  Mesh points;
  points.positions = {{0, 0, 0}, {1, 2, 3}};
  EXPECT_NO_THROW(validate_mesh(points));
}

TEST(ComputeVertexNormals, AreaWeightedWithDefaultForUnusedVertices) {
  Mesh mesh;
  // Vertex 0 is shared by a big triangle facing +z and a small one facing +x.
  mesh.positions = {{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {0, 0, -1}, {0, 1, 0}, {5, 5, 5}};
  mesh.indices = {0, 1, 2, 0, 3, 4};
  compute_vertex_normals(mesh);
  ASSERT_EQ(mesh.normals.size(), 6u);
  // Weights: twice the areas, 4 along +z and 1 along +x.
  const glm::vec3 expected = glm::normalize(glm::vec3(1, 0, 4));
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(mesh.normals[0][c], expected[c], 1e-6f);
  EXPECT_EQ(mesh.normals[1], glm::vec3(0, 0, 1));
  EXPECT_EQ(mesh.normals[3], glm::vec3(1, 0, 0));
  EXPECT_EQ(mesh.normals[5], glm::vec3(0, 0, 1));  // used by no triangle
}

TEST(ComputeVertexNormals, RejectsBadIndices) {
  Mesh mesh = flat_square();
  mesh.indices[4] = 4;
  EXPECT_TRUE(ThrowsError([&] { compute_vertex_normals(mesh); }, ErrorCode::kInvalidMesh,
                          "indices[4]", "vertex count 4"));
}

TEST(FaceNormals, RightHandRuleUnitLengthAndZeroForDegenerate) {
  const std::vector<glm::vec3> p = {{0, 0, 0}, {3, 0, 0}, {0, 3, 0}, {6, 0, 0}};
  const std::vector<glm::dvec3> n = face_normals(p, {0, 1, 2, 0, 2, 1, 0, 1, 3});
  ASSERT_EQ(n.size(), 3u);
  EXPECT_EQ(n[0], glm::dvec3(0, 0, 1));
  EXPECT_EQ(n[1], glm::dvec3(0, 0, -1));
  EXPECT_EQ(n[2], glm::dvec3(0, 0, 0));  // collinear corners
  EXPECT_TRUE(ThrowsError(
      [&] {
        face_normals(p, {0, 1, 9});
      },
      ErrorCode::kInvalidMesh, "indices[2]"));
}

// ---------------------------------------------------------------------------------
// The bundled fish

TEST(BundledFish, AllLoadValid) {
  for (const char* relative : test::kBundledFish) {
    const Mesh mesh = load_mesh(data_path(relative));
    EXPECT_NO_THROW(validate_mesh(mesh)) << relative;
    EXPECT_GT(mesh.triangle_count(), 0u) << relative;
    expect_unit_normals(mesh);
  }
}

TEST(BundledFish, BlubKeepsTheFilesVerticesAndFacesInOrder) {
  for (const char* relative : {"blub/fish.obj", "blub/fish_low_resolution.obj"}) {
    const std::string path = data_path(relative);
    const ObjText obj = parse_obj(path);
    const Mesh mesh = load_mesh(path);
    ASSERT_EQ(mesh.positions, obj.positions) << relative;
    ASSERT_EQ(mesh.triangle_count(), obj.faces.size()) << relative;
    for (std::size_t f = 0; f < obj.faces.size(); ++f) {
      ASSERT_EQ(obj.faces[f].size(), 3u);
      for (std::size_t k = 0; k < 3; ++k) ASSERT_EQ(mesh.indices[3 * f + k], obj.faces[f][k]);
    }
  }
}

TEST(BundledFish, BlubCounts) {
  const Mesh fish = load_mesh(data_path("blub/fish.obj"));
  EXPECT_EQ(fish.vertex_count(), 10786u);
  EXPECT_EQ(fish.triangle_count(), 21568u);
  EXPECT_FALSE(fish.has_tangents());
  EXPECT_TRUE(fish.texcoords.empty());

  const Mesh low = load_mesh(data_path("blub/fish_low_resolution.obj"));
  EXPECT_EQ(low.vertex_count(), 945u);
  EXPECT_EQ(low.triangle_count(), 1886u);
}

TEST(BundledFish, BlubWithoutNormalsGetsAreaWeightedOnes) {
  const Mesh fish = load_mesh(data_path("blub/fish.obj"));  // the file has no "vn"
  const std::vector<glm::dvec3> expected = normals_from_faces(fish);
  for (std::size_t v = 0; v < fish.vertex_count(); ++v) {
    for (int c = 0; c < 3; ++c) {
      ASSERT_NEAR(fish.normals[v][c], expected[v][c], 1e-5) << "normals[" << v << "]";
    }
  }
}

TEST(BundledFish, LowResolutionBlubFoldsPerCornerNormalsIntoVertexNormals) {
  // The file gives one "vn" per face (flat shading); a vertex gets the normalized
  // mean of the "vn" of its corners.
  const std::string path = data_path("blub/fish_low_resolution.obj");
  const ObjText obj = parse_obj(path);
  ASSERT_EQ(obj.normals.size(), 1886u);
  std::vector<glm::dvec3> sums(obj.positions.size(), glm::dvec3(0.0));
  for (std::size_t f = 0; f < obj.faces.size(); ++f) {
    ASSERT_EQ(obj.face_normals[f].size(), obj.faces[f].size());
    for (std::size_t k = 0; k < obj.faces[f].size(); ++k) {
      sums[obj.faces[f][k]] += glm::dvec3(obj.normals[obj.face_normals[f][k]]);
    }
  }
  const Mesh low = load_mesh(path);
  expect_unit_normals(low);
  for (std::size_t v = 0; v < sums.size(); ++v) {
    const glm::dvec3 expected = glm::normalize(sums[v]);
    for (int c = 0; c < 3; ++c) {
      ASSERT_NEAR(low.normals[v][c], expected[c], 1e-6) << "normals[" << v << "]";
    }
  }
}

TEST(BundledFish, ControlMeshPolygonsAreFanTriangulated) {
  // 112 polygons: 100 quads, 8 triangles, 4 pentagons -> 220 triangles.
  const std::string path = data_path("blub/fish_control_mesh.obj");
  const Mesh mesh = load_mesh(path);
  EXPECT_EQ(mesh.vertex_count(), 112u);
  ASSERT_EQ(mesh.triangle_count(), 220u);
  // "f 10/1 2/2 16/3 18/4" -> (9, 1, 15), (9, 15, 17); each polygon fans around its
  // first corner, in file order.
  const ObjText obj = parse_obj(path);
  ASSERT_EQ(obj.faces.size(), 112u);
  std::vector<std::uint32_t> expected;
  for (const std::vector<std::uint32_t>& f : obj.faces) {
    for (std::size_t k = 1; k + 1 < f.size(); ++k) {
      expected.insert(expected.end(), {f[0], f[k], f[k + 1]});
    }
  }
  EXPECT_EQ(mesh.indices, expected);
  EXPECT_EQ(std::vector<std::uint32_t>(mesh.indices.begin(), mesh.indices.begin() + 6),
            (std::vector<std::uint32_t>{9, 1, 15, 9, 15, 17}));
  // 141 "vt" for 112 vertices (texture seams): a vertex keeps the "vt" of its first
  // corner in file order.
  ASSERT_EQ(obj.texcoords.size(), 141u);
  ASSERT_EQ(mesh.texcoords.size(), 112u);
  std::vector<bool> seen(112, false);
  for (std::size_t q = 0; q < obj.faces.size(); ++q) {
    for (std::size_t k = 0; k < obj.faces[q].size(); ++k) {
      const std::uint32_t v = obj.faces[q][k];
      if (seen[v]) continue;
      seen[v] = true;
      EXPECT_EQ(mesh.texcoords[v], obj.texcoords[obj.face_texcoords[q][k]]) << "vertex " << v;
    }
  }
  expect_unit_normals(mesh);
}

TEST(BundledFish, BarramundiCountsAttributesAndNodeRotation) {
  const Mesh fish = load_mesh(data_path("barramundi/BarramundiFish.gltf"));  // PNGs are missing
  EXPECT_EQ(fish.vertex_count(), 2188u);
  EXPECT_EQ(fish.triangle_count(), 3864u);
  ASSERT_TRUE(fish.has_tangents());
  ASSERT_EQ(fish.texcoords.size(), 2188u);
  expect_unit_normals(fish);
  for (const glm::vec4& t : fish.tangents) {
    ASSERT_NEAR(glm::length(glm::vec3(t)), 1.0f, 1e-5f);
    ASSERT_EQ(std::fabs(t.w), 1.0f);
  }
  // The POSITION accessor spans x [-0.0738, 0.0691], z [-0.3177, 0.3254]; the node
  // turns it 180 degrees about y, which negates x and z.
  const Box box = bounding_box(fish.positions);
  EXPECT_NEAR(box.lo.x, -0.0690619648, 1e-6);
  EXPECT_NEAR(box.hi.x, 0.073841624, 1e-6);
  EXPECT_NEAR(box.lo.y, -0.000878453255, 1e-6);
  EXPECT_NEAR(box.hi.y, 0.2866283, 1e-6);
  EXPECT_NEAR(box.lo.z, -0.3253729, 1e-6);
  EXPECT_NEAR(box.hi.z, 0.317738324, 1e-6);
}

TEST(BundledFish, BarramundiGeometryOnlyMatchesTheFullFile) {
  const Mesh full = load_mesh(data_path("barramundi/BarramundiFish.gltf"));
  const Mesh geometry = load_mesh(data_path("barramundi/BarramundiFish_geometry_only.gltf"));
  EXPECT_EQ(full.positions, geometry.positions);
  EXPECT_EQ(full.normals, geometry.normals);
  EXPECT_EQ(full.tangents, geometry.tangents);
  EXPECT_EQ(full.texcoords, geometry.texcoords);
  EXPECT_EQ(full.indices, geometry.indices);
}

// ---------------------------------------------------------------------------------
// Round trips

class RoundTrip : public ::testing::TestWithParam<const char*> {};

// OBJ, PLY, OFF keep vertices (order included), faces, normals and texcoords; glTF
// and GLB also tangents. Positions come back bit-identical (text with 9 significant
// digits, binary floats); normals are renormalized on loading.
TEST_P(RoundTrip, KeepsWhatTheFormatCarries) {
  const std::string extension = GetParam();
  const bool gltf = extension == "gltf" || extension == "glb";
  for (const Mesh& original :
       {decorated_fish(), load_mesh(data_path("barramundi/BarramundiFish.gltf"))}) {
    const std::string path = temp_path("round_trip." + extension);
    save_mesh(path, original);
    const Mesh loaded = load_mesh(path);
    ASSERT_EQ(loaded.vertex_count(), original.vertex_count()) << extension;
    EXPECT_EQ(loaded.positions, original.positions);
    EXPECT_EQ(loaded.indices, original.indices);
    expect_near(loaded.normals, original.normals, 1e-5f, "normals");
    ASSERT_EQ(loaded.texcoords.size(), original.texcoords.size());
    for (std::size_t v = 0; v < loaded.texcoords.size(); ++v) {
      ASSERT_NEAR(loaded.texcoords[v].x, original.texcoords[v].x, 1e-6f) << v;
      ASSERT_NEAR(loaded.texcoords[v].y, original.texcoords[v].y, 1e-6f) << v;
    }
    if (gltf) {
      ASSERT_EQ(loaded.tangents.size(), original.tangents.size());
      for (std::size_t v = 0; v < loaded.tangents.size(); ++v) {
        for (int c = 0; c < 4; ++c) {
          ASSERT_NEAR(loaded.tangents[v][c], original.tangents[v][c], 1e-6f)
              << "tangents[" << v << "]";
        }
      }
    } else {
      EXPECT_FALSE(loaded.has_tangents());
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Formats, RoundTrip, ::testing::Values("obj", "ply", "off", "gltf", "glb"));

// STL stores separate triangles with facet normals only. What comes back: the same
// triangles in the same order with bit-identical corner positions; one vertex per
// distinct position (STL readers merge equal points), numbered in order of first
// use; area-weighted normals; no texcoords or tangents.
TEST(RoundTripStl, KeepsTrianglesAndPositionsAndRecomputesNormals) {
  for (const Mesh& original :
       {decorated_fish(), load_mesh(data_path("barramundi/BarramundiFish.gltf"))}) {
    const std::string path = temp_path("round_trip.stl");
    save_mesh(path, original);
    const Mesh loaded = load_mesh(path);
    ASSERT_EQ(loaded.triangle_count(), original.triangle_count());
    for (std::size_t i = 0; i < original.indices.size(); ++i) {
      ASSERT_EQ(loaded.positions[loaded.indices[i]], original.positions[original.indices[i]]) << i;
    }
    const auto less = [](const glm::vec3& a, const glm::vec3& b) {
      return std::tie(a.x, a.y, a.z) < std::tie(b.x, b.y, b.z);
    };
    std::map<glm::vec3, std::uint32_t, decltype(less)> first_use(less);
    for (const std::uint32_t index : original.indices) {
      first_use.emplace(original.positions[index], static_cast<std::uint32_t>(first_use.size()));
    }
    EXPECT_EQ(loaded.vertex_count(), first_use.size());
    const std::vector<glm::dvec3> expected = normals_from_faces(loaded);
    for (std::size_t v = 0; v < loaded.vertex_count(); ++v) {
      EXPECT_EQ(first_use.at(loaded.positions[v]), v);
      for (int c = 0; c < 3; ++c) ASSERT_NEAR(loaded.normals[v][c], expected[v][c], 1e-5);
    }
    EXPECT_TRUE(loaded.texcoords.empty());
    EXPECT_FALSE(loaded.has_tangents());
  }
}

TEST(RoundTripStl, MeshNumberedInOrderOfFirstUseComesBackIdentical) {
  const Mesh square = flat_square();  // vertices first used in order 0, 1, 2, 3
  const std::string path = temp_path("square.stl");
  save_mesh(path, square);
  const Mesh loaded = load_mesh(path);
  EXPECT_EQ(loaded.positions, square.positions);
  EXPECT_EQ(loaded.indices, square.indices);
  for (const glm::vec3& n : loaded.normals) EXPECT_EQ(n, glm::vec3(0, 0, 1));
}

TEST(RoundTripShapes, NonManifoldMeshKeepsItsVerticesAndFaces) {
  // Three triangles on one edge, plus an unused vertex: no halfedge structure in the
  // way, so nothing is split or dropped.
  Mesh fan;
  fan.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {9, 9, 9}};
  fan.indices = {0, 1, 2, 1, 0, 3, 0, 1, 4};
  compute_vertex_normals(fan);
  for (const char* extension : {"obj", "ply", "off", "gltf", "glb"}) {
    const std::string path = temp_path(std::string("fan.") + extension);
    save_mesh(path, fan);
    const Mesh loaded = load_mesh(path);
    EXPECT_EQ(loaded.positions, fan.positions) << extension;
    EXPECT_EQ(loaded.indices, fan.indices) << extension;
    expect_near(loaded.normals, fan.normals, 1e-6f, extension);
  }
}

TEST(RoundTripShapes, OffPolygonsAreFanTriangulated) {
  const std::string path = temp_path("pentagon.off");
  write_file(path, "OFF\n5 1 0\n0 0 0\n1 0 0\n2 1 0\n1 2 0\n0 1 0\n5 0 1 2 3 4\n");
  const Mesh mesh = load_mesh(path);
  EXPECT_EQ(mesh.indices, (std::vector<std::uint32_t>{0, 1, 2, 0, 2, 3, 0, 3, 4}));
  for (const glm::vec3& n : mesh.normals) EXPECT_EQ(n, glm::vec3(0, 0, 1));
}

TEST(LoadMesh, ConcurrentLoadsAgree) {
  const Mesh expected = load_mesh(data_path("blub/fish_low_resolution.obj"));
  std::vector<Mesh> meshes(8);
  std::vector<std::thread> threads;
  for (std::size_t i = 0; i < meshes.size(); ++i) {
    const char* file =
        i % 2 == 0 ? "blub/fish_low_resolution.obj" : "barramundi/BarramundiFish.gltf";
    threads.emplace_back([&meshes, i, file] { meshes[i] = load_mesh(data_path(file)); });
  }
  for (std::thread& thread : threads) thread.join();
  for (std::size_t i = 0; i < meshes.size(); i += 2) {
    EXPECT_EQ(meshes[i].positions, expected.positions);
    EXPECT_EQ(meshes[i].normals, expected.normals);
    EXPECT_EQ(meshes[i + 1].vertex_count(), 2188u);
  }
}

TEST(SaveMesh, MeshWithoutNormalsIsWrittenWithComputedOnes) {
  for (const char* extension : {"obj", "ply", "off", "gltf", "glb"}) {
    const std::string path = temp_path(std::string("square.") + extension);
    save_mesh(path, flat_square());
    const Mesh loaded = load_mesh(path);
    ASSERT_EQ(loaded.normals.size(), 4u) << extension;
    for (const glm::vec3& n : loaded.normals) EXPECT_EQ(n, glm::vec3(0, 0, 1)) << extension;
  }
}

TEST(SaveMesh, ExtensionsAreCaseInsensitiveAndAnExistingFileIsReplaced) {
  const Mesh fish = decorated_fish();
  const std::string path = temp_path("FISH.Ply");
  write_file(path, "old content");
  save_mesh(path, fish);
  EXPECT_EQ(load_mesh(path).positions, fish.positions);
  EXPECT_EQ(folder_entries(fs::path(path).parent_path()), std::vector<std::string>{"FISH.Ply"});
}

TEST(SaveMesh, GltfIsSelfContainedAndGlbIsBinary) {
  const Mesh fish = load_mesh(data_path("barramundi/BarramundiFish.gltf"));
  const std::string gltf = temp_path("fish.gltf");
  save_mesh(gltf, fish);
  const std::string text = read_file(gltf);
  EXPECT_NE(text.find("data:application/octet-stream;base64,"), std::string::npos);
  EXPECT_NE(text.find("\"min\""), std::string::npos);
  EXPECT_NE(text.find("\"max\""), std::string::npos);
  EXPECT_EQ(folder_entries(fs::path(gltf).parent_path()), std::vector<std::string>{"fish.gltf"});
  const std::string glb = temp_path("fish.glb");
  save_mesh(glb, fish);
  EXPECT_EQ(read_file(glb).substr(0, 4), "glTF");
}

// ---------------------------------------------------------------------------------
// Crafted glTF scenes

// Builds a small glTF file with one base64-embedded buffer.
class GltfBuilder {
 public:
  // Appends `bytes` (4-byte aligned) as a bufferView; returns its index.
  int view(const std::string& bytes, std::size_t stride = 0) {
    while (bin_.size() % 4 != 0) bin_.push_back('\0');
    std::string json = "{\"buffer\":0,\"byteOffset\":" + std::to_string(bin_.size()) +
                       ",\"byteLength\":" + std::to_string(bytes.size());
    if (stride != 0) json += ",\"byteStride\":" + std::to_string(stride);
    views_.push_back(json + "}");
    bin_ += bytes;
    return static_cast<int>(views_.size() - 1);
  }
  template <typename T>
  int view(const std::vector<T>& values, std::size_t stride = 0) {
    return view(
        std::string(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(T)),
        stride);
  }
  // Adds an accessor; `extra` is more JSON members (",\"normalized\":true").
  int accessor(int view_index, int component_type, std::size_t count, const std::string& type,
               std::size_t byte_offset = 0, const std::string& extra = "") {
    accessors_.push_back("{\"bufferView\":" + std::to_string(view_index) +
                         ",\"byteOffset\":" + std::to_string(byte_offset) + ",\"componentType\":" +
                         std::to_string(component_type) + ",\"count\":" + std::to_string(count) +
                         ",\"type\":\"" + type + "\"" + extra + "}");
    return static_cast<int>(accessors_.size() - 1);
  }
  // Writes the file; `members` holds the remaining top-level JSON members
  // ("\"meshes\":[...],\"nodes\":[...]").
  std::string write(const std::string& file_name, const std::string& members) const {
    const std::string path = temp_path(file_name);
    write_file(path, "{\"asset\":{\"version\":\"2.0\"},\"buffers\":[{\"byteLength\":" +
                         std::to_string(bin_.size()) +
                         ",\"uri\":\"data:application/octet-stream;base64," + base64(bin_) +
                         "\"}],\"bufferViews\":[" + join(views_) + "],\"accessors\":[" +
                         join(accessors_) + "]," + members + "}");
    return path;
  }

 private:
  static std::string join(const std::vector<std::string>& items) {
    std::string out;
    for (const std::string& item : items) out += (out.empty() ? "" : ",") + item;
    return out;
  }
  static std::string base64(const std::string& bytes) {
    static const char kAlphabet[] =
        "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    for (std::size_t i = 0; i < bytes.size(); i += 3) {
      const std::size_t n = std::min<std::size_t>(3, bytes.size() - i);
      std::uint32_t chunk = 0;
      for (std::size_t k = 0; k < 3; ++k) {
        chunk = chunk << 8 | (k < n ? static_cast<unsigned char>(bytes[i + k]) : 0u);
      }
      for (std::size_t k = 0; k < 4; ++k) {
        out += k <= n ? kAlphabet[(chunk >> (18 - 6 * k)) & 63u] : '=';
      }
    }
    return out;
  }

  std::string bin_;
  std::vector<std::string> views_;
  std::vector<std::string> accessors_;
};

constexpr int kFloat = 5126, kU8 = 5121, kU16 = 5123, kU32 = 5125;

// One triangle in the xy plane facing +z: POSITION, NORMAL, TANGENT and u16 indices;
// accessors 0..3.
GltfBuilder triangle_builder() {
  GltfBuilder b;
  b.accessor(b.view(std::vector<float>{0, 0, 0, 1, 0, 0, 0, 1, 0}), kFloat, 3, "VEC3");
  b.accessor(b.view(std::vector<float>{0, 0, 1, 0, 0, 1, 0, 0, 1}), kFloat, 3, "VEC3");
  b.accessor(b.view(std::vector<float>{1, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 1}), kFloat, 3, "VEC4");
  b.accessor(b.view(std::vector<std::uint16_t>{0, 1, 2}), kU16, 3, "SCALAR");
  return b;
}

const char* const kTriangleMesh =
    "\"meshes\":[{\"name\":\"tri\",\"primitives\":[{\"attributes\":{\"POSITION\":0,"
    "\"NORMAL\":1,\"TANGENT\":2},\"indices\":3}]}]";

TEST(GltfScene, NodeHierarchyTrsMatrixAndMirroring) {
  // Root: translation (1, 2, 3); child: mirror in x. A second root node holds the
  // same mesh through a matrix (translation (0, 0, 5)).
  const std::string path = triangle_builder().write(
      "scene.gltf",
      std::string(kTriangleMesh) +
          ",\"nodes\":[{\"translation\":[1,2,3],\"children\":[1]},{\"mesh\":0,\"scale\":[-1,1,1]},"
          "{\"mesh\":0,\"matrix\":[1,0,0,0,0,1,0,0,0,0,1,0,0,0,5,1]}],"
          "\"scenes\":[{\"nodes\":[2]},{\"nodes\":[0,2]}],\"scene\":1");
  const Mesh mesh = load_mesh(path);
  ASSERT_EQ(mesh.vertex_count(), 6u);
  EXPECT_EQ(mesh.positions[0], glm::vec3(1, 2, 3));
  EXPECT_EQ(mesh.positions[1], glm::vec3(0, 2, 3));  // x mirrored, then translated
  EXPECT_EQ(mesh.positions[2], glm::vec3(1, 3, 3));
  EXPECT_EQ(mesh.positions[4], glm::vec3(1, 0, 5));
  // The mirror flips the winding back to counter-clockwise about the normal, and
  // the tangent's handedness.
  EXPECT_EQ(mesh.indices, (std::vector<std::uint32_t>{0, 2, 1, 3, 4, 5}));
  EXPECT_EQ(mesh.normals[0], glm::vec3(0, 0, 1));
  EXPECT_EQ(mesh.tangents[0], glm::vec4(-1, 0, 0, -1));
  EXPECT_EQ(mesh.tangents[3], glm::vec4(1, 0, 0, 1));
  const std::vector<glm::dvec3> faces = face_normals(mesh.positions, mesh.indices);
  EXPECT_EQ(faces[0], glm::dvec3(0, 0, 1));
}

TEST(GltfScene, WithoutScenesEveryRootNodeCounts) {
  const std::string path = triangle_builder().write(
      "roots.gltf", std::string(kTriangleMesh) +
                        ",\"nodes\":[{\"mesh\":0,\"children\":[1]},{\"mesh\":0},{\"mesh\":0}]");
  EXPECT_EQ(load_mesh(path).vertex_count(), 9u);
}

TEST(GltfScene, InterleavedStrideOffsetsU8IndicesNormalizedTexcoordsAndNoIndices) {
  GltfBuilder b;
  // Interleaved position + normal, 24-byte stride; the normals start at byte 12.
  const int interleaved = b.view(std::vector<float>{0, 0, 0, 0, 0, 2,  //
                                                    1, 0, 0, 0, 0, 2,  //
                                                    0, 1, 0, 0, 0, 2},
                                 24);
  b.accessor(interleaved, kFloat, 3, "VEC3");
  b.accessor(interleaved, kFloat, 3, "VEC3", 12);
  b.accessor(b.view(std::vector<std::uint8_t>{0, 255, 255, 0, 51, 102, 0, 0}), kU8, 3, "VEC2", 0,
             ",\"normalized\":true");
  b.accessor(b.view(std::vector<std::uint8_t>{2, 1, 0, 0}), kU8, 3, "SCALAR");
  const std::string path = b.write(
      "interleaved.gltf",
      "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0,\"NORMAL\":1,\"TEXCOORD_0\":2},"
      "\"indices\":3},{\"attributes\":{\"POSITION\":0}}]}],\"nodes\":[{\"mesh\":0}],"
      "\"scenes\":[{\"nodes\":[0]}]");
  const Mesh mesh = load_mesh(path);
  ASSERT_EQ(mesh.vertex_count(), 6u);
  EXPECT_EQ(mesh.positions[1], glm::vec3(1, 0, 0));
  EXPECT_EQ(mesh.normals[1], glm::vec3(0, 0, 1));  // normalized
  EXPECT_EQ(mesh.texcoords[0], glm::vec2(0, 1));
  EXPECT_EQ(mesh.texcoords[1], glm::vec2(1, 0));
  EXPECT_NEAR(mesh.texcoords[2].y, 0.4f, 1e-6f);
  EXPECT_EQ(mesh.texcoords[4], glm::vec2(0, 0));  // second primitive has none
  EXPECT_EQ(mesh.indices, (std::vector<std::uint32_t>{2, 1, 0, 3, 4, 5}));
  // Second primitive had no NORMAL: computed. Its winding 3, 4, 5 faces +z.
  EXPECT_EQ(mesh.normals[4], glm::vec3(0, 0, 1));
  EXPECT_EQ(mesh.normals[0], glm::vec3(0, 0, 1));
}

TEST(GltfScene, UnsupportedContentIsAFormatErrorNamingTheField) {
  {  // LINES primitive after a good one
    const std::string path = triangle_builder().write(
        "lines.gltf",
        "\"meshes\":[{\"name\":\"fin\",\"primitives\":[{\"attributes\":{\"POSITION\":0},"
        "\"indices\":3},"
        "{\"attributes\":{\"POSITION\":0},\"mode\":1}]}],\"nodes\":[{\"mesh\":0}]");
    EXPECT_TRUE(ThrowsError(
        [&] { load_mesh(path); }, ErrorCode::kFormat, "meshes[0].primitives[1]",
        "meshes[0].primitives[1]: mode 1 (LINES) is not supported (only TRIANGLES); mesh 'fin'"));
  }
  {  // NORMAL with fewer elements than POSITION
    GltfBuilder b = triangle_builder();
    b.accessor(b.view(std::vector<float>{0, 0, 1, 0, 0, 1}), kFloat, 2, "VEC3");
    const std::string path =
        b.write("short_normals.gltf",
                "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0,\"NORMAL\":4}}]}],"
                "\"nodes\":[{\"mesh\":0}]");
    EXPECT_TRUE(ThrowsError([&] { load_mesh(path); }, ErrorCode::kFormat,
                            "meshes[0].primitives[0].NORMAL",
                            "has 2 elements, but POSITION has 3"));
  }
  {  // sparse accessor
    GltfBuilder b = triangle_builder();
    const int sparse_indices = b.view(std::vector<std::uint32_t>{1});
    const int sparse_values = b.view(std::vector<float>{5, 5, 5});
    b.accessor(0, kFloat, 3, "VEC3", 0,
               ",\"sparse\":{\"count\":1,\"indices\":{\"bufferView\":" +
                   std::to_string(sparse_indices) + ",\"componentType\":" + std::to_string(kU32) +
                   "},\"values\":{\"bufferView\":" + std::to_string(sparse_values) + "}}");
    const std::string path = b.write("sparse.gltf",
                                     "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":4}"
                                     "}]}],\"nodes\":[{\"mesh\":0}]");
    EXPECT_TRUE(ThrowsError([&] { load_mesh(path); }, ErrorCode::kFormat,
                            "meshes[0].primitives[0].POSITION", "sparse"));
  }
  {  // accessor reaching past its bufferView
    GltfBuilder b = triangle_builder();
    b.accessor(0, kFloat, 4, "VEC3");
    const std::string path = b.write("overrun.gltf",
                                     "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":4}"
                                     "}]}],\"nodes\":[{\"mesh\":0}]");
    EXPECT_TRUE(ThrowsError([&] { load_mesh(path); }, ErrorCode::kFormat,
                            "meshes[0].primitives[0].POSITION", "exceeds bufferView 0"));
  }
  {  // index out of range
    GltfBuilder b = triangle_builder();
    b.accessor(b.view(std::vector<std::uint16_t>{0, 1, 7}), kU16, 3, "SCALAR");
    const std::string path =
        b.write("bad_index.gltf",
                "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"indices\":4}]}],"
                "\"nodes\":[{\"mesh\":0}]");
    EXPECT_TRUE(ThrowsError([&] { load_mesh(path); }, ErrorCode::kInvalidMesh,
                            "meshes[0].primitives[0].indices[2]",
                            "= 7 is out of range (vertex count 3)"));
  }
  {  // NaN position
    GltfBuilder b;
    const float nan = std::numeric_limits<float>::quiet_NaN();
    b.accessor(b.view(std::vector<float>{0, 0, 0, 1, nan, 0, 0, 1, 0}), kFloat, 3, "VEC3");
    const std::string path =
        b.write("nan.gltf",
                "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0}}]}],"
                "\"nodes\":[{\"mesh\":0}]");
    EXPECT_TRUE(ThrowsError([&] { load_mesh(path); }, ErrorCode::kInvalidMesh,
                            "meshes[0].primitives[0].POSITION[1].y", "is NaN"));
  }
}

TEST(GltfScene, MissingBufferFileIsAnIoError) {
  const std::string path = temp_path("BarramundiFish.gltf");
  fs::copy_file(data_path("barramundi/BarramundiFish.gltf"), path);  // without its .bin
  EXPECT_TRUE(ThrowsError([&] { load_mesh(path); }, ErrorCode::kIo, "path", "BarramundiFish.gltf"));
}

// ---------------------------------------------------------------------------------
// Load errors

TEST(LoadErrors, MissingFileOrFolderIsAnIoError) {
  const std::string missing = temp_path("missing.obj");
  EXPECT_TRUE(
      ThrowsError([&] { load_mesh(missing); }, ErrorCode::kIo, "path", "'" + missing + "'"));
  const std::string folder = temp_path("folder.ply");
  fs::create_directory(folder);
  EXPECT_TRUE(ThrowsError([&] { load_mesh(folder); }, ErrorCode::kIo, "path", "directory"));
}

TEST(LoadErrors, UnknownExtensionIsAFormatError) {
  const std::string path = temp_path("x.foo");
  write_file(path, "v 0 0 0\n");
  EXPECT_TRUE(
      ThrowsError([&] { load_mesh(path); }, ErrorCode::kFormat, "path",
                  "unsupported extension '.foo' (supported: .obj .ply .off .stl .gltf .glb)"));
  const std::string bare = temp_path("no_extension");
  write_file(bare, "v 0 0 0\n");
  EXPECT_TRUE(ThrowsError([&] { load_mesh(bare); }, ErrorCode::kFormat, "path", "no extension"));
}

TEST(LoadErrors, EmptyAndGarbageFilesAreFormatErrors) {
  for (const char* extension : {"obj", "ply", "off", "stl", "gltf", "glb"}) {
    const std::string empty = temp_path(std::string("empty.") + extension);
    write_file(empty, "");
    EXPECT_TRUE(ThrowsError([&] { load_mesh(empty); }, ErrorCode::kFormat, "path", "empty"))
        << extension;
    const std::string garbage = temp_path(std::string("garbage.") + extension);
    write_file(garbage, "this is not a mesh\n\x01\x02\x03 {[ nonsense ]}\n");
    EXPECT_TRUE(ThrowsError([&] { load_mesh(garbage); }, ErrorCode::kFormat, "", "garbage."))
        << extension;
  }
}

TEST(LoadErrors, NanPositionInAFileIsAnInvalidMesh) {
  // Binary PLY: three vertices, the second one's y is NaN, one triangle.
  std::string ply =
      "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n"
      "property float y\nproperty float z\nelement face 1\n"
      "property list uchar int vertex_indices\nend_header\n";
  const float nan = std::numeric_limits<float>::quiet_NaN();
  for (const float value : {0.0f, 0.0f, 0.0f, 1.0f, nan, 0.0f, 0.0f, 1.0f, 0.0f}) {
    append_bytes(ply, value);
  }
  append_bytes(ply, std::uint8_t{3});
  for (const std::int32_t index : {0, 1, 2}) append_bytes(ply, index);
  const std::string path = temp_path("nan.ply");
  write_file(path, ply);
  EXPECT_TRUE(ThrowsError([&] { load_mesh(path); }, ErrorCode::kInvalidMesh, "vertex[1].y",
                          "vertex[1].y (byte 189): is NaN"));
}

TEST(LoadErrors, IndexOutOfRangeInAFileIsAnInvalidMesh) {
  const std::string path = temp_path("bad_index.obj");
  write_file(path, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 99999\n");
  EXPECT_TRUE(ThrowsError([&] { load_mesh(path); }, ErrorCode::kInvalidMesh, "line 5",
                          "line 5: face corner 3: v index 99999 is out of range (3 'v' lines"));
  const std::string off = temp_path("bad_index.off");
  write_file(off, "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n");
  EXPECT_TRUE(ThrowsError([&] { load_mesh(off); }, ErrorCode::kInvalidMesh, "line 6",
                          "face 0 corner 3: vertex index 3 is out of range (3 vertices)"));
}

TEST(LoadErrors, HeaderCountsBeyondTheFileAreAFormatError) {
  // OpenMesh's OFF reader would repeat the last face a billion times.
  const std::string path = temp_path("truncated.off");
  write_file(path, "OFF\n3 1000000000 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  EXPECT_TRUE(ThrowsError([&] { load_mesh(path); }, ErrorCode::kFormat, "line 2",
                          "1000000000 faces, but the 26 bytes after it cannot hold them"));
}

TEST(LoadErrors, MissingNormalsAreComputedAndAgreeWithFaceNormals) {
  const std::string path = temp_path("square.obj");
  write_file(path, "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n");
  const Mesh mesh = load_mesh(path);
  ASSERT_EQ(mesh.indices, (std::vector<std::uint32_t>{0, 1, 2, 0, 2, 3}));
  const std::vector<glm::dvec3> faces = face_normals(mesh.positions, mesh.indices);
  for (const glm::vec3& n : mesh.normals) {
    EXPECT_EQ(glm::dvec3(n), faces[0]);
    EXPECT_EQ(glm::dvec3(n), faces[1]);
  }
}

TEST(LoadErrors, LibraryIsQuiet) {
  const std::string with_mtllib = temp_path("quiet.obj");
  write_file(with_mtllib,
             "mtllib missing.mtl\nusemtl nothing\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  const std::string garbage = temp_path("quiet.ply");
  write_file(garbage, "ply\nnonsense\n");
  ::testing::internal::CaptureStderr();
  ::testing::internal::CaptureStdout();
  EXPECT_NO_THROW(load_mesh(with_mtllib));
  EXPECT_ANY_THROW(load_mesh(garbage));
  EXPECT_NO_THROW(load_mesh(data_path("barramundi/BarramundiFish.gltf")));
  for (const char* extension : {"obj", "ply", "off", "stl", "gltf", "glb"}) {
    EXPECT_NO_THROW(save_mesh(temp_path(std::string("quiet.") + extension), flat_square()));
  }
  const std::string out = ::testing::internal::GetCapturedStdout();
  const std::string err = ::testing::internal::GetCapturedStderr();
  EXPECT_EQ(out, "");
  EXPECT_EQ(err, "");
}

// ---------------------------------------------------------------------------------
// Save errors: the target is never created or changed, no temporary file is left

class SaveErrors : public ::testing::TestWithParam<const char*> {};

TEST_P(SaveErrors, InvalidMeshLeavesTheTargetAlone) {
  const std::string extension = GetParam();
  Mesh bad = decorated_fish();
  bad.positions[12].y = std::numeric_limits<float>::quiet_NaN();

  const std::string fresh = temp_path("fresh." + extension);
  EXPECT_TRUE(ThrowsError([&] { save_mesh(fresh, bad); }, ErrorCode::kInvalidMesh,
                          "positions[12].y", "positions[12].y is NaN"));
  EXPECT_FALSE(fs::exists(fresh));
  EXPECT_TRUE(fs::is_empty(fs::path(fresh).parent_path()));

  const std::string existing = temp_path("existing." + extension);
  save_mesh(existing, flat_square());
  const std::string before = read_file(existing);
  bad = decorated_fish();
  bad.indices[7] = 99999;
  EXPECT_TRUE(ThrowsError([&] { save_mesh(existing, bad); }, ErrorCode::kInvalidMesh, "indices[7]",
                          "indices[7] = 99999 is out of range (vertex count 945)"));
  bad = decorated_fish();
  bad.normals.resize(10);
  EXPECT_TRUE(ThrowsError([&] { save_mesh(existing, bad); }, ErrorCode::kInvalidMesh, "normals",
                          "10 entries"));
  EXPECT_EQ(read_file(existing), before);
  EXPECT_EQ(folder_entries(fs::path(existing).parent_path()),
            std::vector<std::string>{"existing." + extension});
}

INSTANTIATE_TEST_SUITE_P(Formats, SaveErrors,
                         ::testing::Values("obj", "ply", "off", "stl", "gltf", "glb"));

TEST(SaveErrorsOther, UnknownExtensionMissingFolderAndDirectoryTarget) {
  const std::string foo = temp_path("x.foo");
  EXPECT_TRUE(ThrowsError([&] { save_mesh(foo, flat_square()); }, ErrorCode::kFormat, "path",
                          "unsupported extension '.foo'"));
  EXPECT_FALSE(fs::exists(foo));

  const std::string no_folder = temp_path("nowhere") + "/fish.obj";
  EXPECT_TRUE(ThrowsError([&] { save_mesh(no_folder, flat_square()); }, ErrorCode::kIo, "path",
                          "does not exist"));
  EXPECT_FALSE(fs::exists(no_folder));

  const std::string folder = temp_path("folder.obj");
  fs::create_directory(folder);
  EXPECT_TRUE(
      ThrowsError([&] { save_mesh(folder, flat_square()); }, ErrorCode::kIo, "path", "directory"));
  EXPECT_TRUE(fs::is_empty(folder));
}

TEST(SaveErrorsOther, FormatLimitFailsAfterTheTemporaryFileAndStillLeavesNoTrace) {
  // glTF needs a triangle; the writer fails once the temporary file exists.
  Mesh points;
  points.positions = {{0, 0, 0}, {1, 0, 0}};
  const std::string path = temp_path("points.glb");
  write_file(path, "previous");
  EXPECT_TRUE(ThrowsError([&] { save_mesh(path, points); }, ErrorCode::kInvalidMesh, "indices",
                          "triangle"));
  EXPECT_EQ(read_file(path), "previous");
  EXPECT_EQ(folder_entries(fs::path(path).parent_path()), std::vector<std::string>{"points.glb"});
}

// ---------------------------------------------------------------------------------
// Face groups: OBJ "g" (or "o") lines and glTF primitives

::testing::AssertionResult HasGroups(
    const Mesh& mesh,
    const std::vector<std::tuple<std::string, std::size_t, std::size_t>>& expected) {
  std::vector<std::tuple<std::string, std::size_t, std::size_t>> actual;
  for (const FaceGroup& g : mesh.groups) {
    actual.emplace_back(g.name, g.first_triangle, g.triangle_count);
  }
  if (actual == expected) return ::testing::AssertionSuccess();
  ::testing::AssertionResult failure = ::testing::AssertionFailure();
  failure << "groups:";
  for (const auto& [name, first, count] : actual) {
    failure << " {'" << name << "', " << first << ", " << count << "}";
  }
  return failure;
}

TEST(FaceGroups, ObjGroupLinesCoverTheTrianglesOfTheFacesAfterThem) {
  // Faces: an ungrouped triangle, a quad and a pentagon in "fin" (2 + 3 triangles),
  // a bare "g" (no group), "body" with a negative-index triangle, then "fin" again (a
  // second run of the same name). The "o" line is ignored because the file has "g"
  // lines.
  const std::string path = temp_path("groups.obj");
  write_file(path,
             "# groups\n"
             "o fish\n"
             "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0.5 1.5 0\nv 2 0 0\nvt 0 0\n"
             "f 1 2 3\n"
             "g fin\n"
             "f 1 2 3 4\n"
             "f 1/1 2/1 3/1 5/1 4/1\n"
             "g\n"
             "f 2 6 3\n"
             "  g   body  \r\n"
             "f -5 -1 -4\n"
             "g fin\n"
             "f 2 6 3\n");
  const Mesh mesh = load_mesh(path);
  ASSERT_EQ(mesh.triangle_count(), 9u);
  EXPECT_TRUE(HasGroups(mesh, {{"fin", 1, 5}, {"body", 7, 1}, {"fin", 8, 1}}));
  EXPECT_EQ(std::vector<std::uint32_t>(mesh.indices.begin() + 21, mesh.indices.begin() + 24),
            (std::vector<std::uint32_t>{1, 5, 2}));  // "body": -5 -1 -4 after 6 "v" lines
}

TEST(FaceGroups, ObjObjectLinesCountWhenThereIsNoGroupLine) {
  const std::string path = temp_path("objects.obj");
  write_file(path,
             "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
             "o first\nf 1 2 3\nf 1 3 4\n"
             "o second\nf 1 2 3 4\n");
  EXPECT_TRUE(HasGroups(load_mesh(path), {{"first", 0, 2}, {"second", 2, 2}}));
}

TEST(FaceGroups, FilesWithoutGroupsAndSavedMeshesHaveNone) {
  for (const char* relative : {"blub/fish.obj", "blub/fish_low_resolution.obj"}) {
    EXPECT_TRUE(load_mesh(data_path(relative)).groups.empty()) << relative;
  }
  Mesh square = flat_square();
  square.groups = {{"ignored", 0, 1}};
  for (const char* extension : {"obj", "ply", "off", "stl"}) {
    const std::string path = temp_path(std::string("square.") + extension);
    save_mesh(path, square);
    EXPECT_TRUE(load_mesh(path).groups.empty()) << extension;
  }
}

TEST(FaceGroups, GltfPrimitivesAreGroupsNamedByMeshAndPrimitive) {
  // Saved glTF: one unnamed mesh with one primitive.
  const Mesh low = load_mesh(data_path("blub/fish_low_resolution.obj"));
  const std::string path = temp_path("fish.glb");
  save_mesh(path, low);
  EXPECT_TRUE(HasGroups(load_mesh(path), {{"0/0", 0, low.triangle_count()}}));

  // The Barramundi: every triangle in exactly one group, groups in order.
  const Mesh fish = load_mesh(data_path("barramundi/BarramundiFish.gltf"));
  ASSERT_FALSE(fish.groups.empty());
  std::size_t next = 0;
  for (const FaceGroup& g : fish.groups) {
    EXPECT_EQ(g.first_triangle, next) << g.name;
    EXPECT_GT(g.triangle_count, 0u) << g.name;
    EXPECT_NE(g.name.find('/'), std::string::npos) << g.name;
    next += g.triangle_count;
  }
  EXPECT_EQ(next, fish.triangle_count());
}

}  // namespace
}  // namespace finflex
