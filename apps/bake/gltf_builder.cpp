#include "gltf_builder.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>

#include "finflex/error.hpp"

namespace finflex::bake {

namespace {

template <int N>
void set_bounds(tinygltf::Accessor& accessor, const std::vector<glm::vec<N, float>>& values) {
  glm::vec<N, double> lo(std::numeric_limits<double>::infinity());
  glm::vec<N, double> hi(-std::numeric_limits<double>::infinity());
  for (const auto& v : values) {
    lo = glm::min(lo, glm::vec<N, double>(v));
    hi = glm::max(hi, glm::vec<N, double>(v));
  }
  accessor.minValues.assign(&lo[0], &lo[0] + N);
  accessor.maxValues.assign(&hi[0], &hi[0] + N);
}

}  // namespace

GltfBuilder::GltfBuilder() {
  model_.asset.version = "2.0";
  model_.asset.generator = "FinFlex bake";
  model_.buffers.emplace_back();
}

int GltfBuilder::add_view(const void* bytes, std::size_t size, int target) {
  std::vector<unsigned char>& data = model_.buffers[0].data;
  data.resize((data.size() + 3) / 4 * 4, 0);  // every view 4-byte aligned
  tinygltf::BufferView view;
  view.buffer = 0;
  view.byteOffset = data.size();
  view.byteLength = size;
  view.target = target;
  const auto* begin = static_cast<const unsigned char*>(bytes);
  data.insert(data.end(), begin, begin + size);
  model_.bufferViews.push_back(view);
  return static_cast<int>(model_.bufferViews.size() - 1);
}

int GltfBuilder::add_accessor(const void* bytes, std::size_t count, std::size_t element_bytes,
                              int type, int component_type, int target) {
  tinygltf::Accessor accessor;
  accessor.bufferView = add_view(bytes, count * element_bytes, target);
  accessor.componentType = component_type;
  accessor.count = count;
  accessor.type = type;
  model_.accessors.push_back(accessor);
  return static_cast<int>(model_.accessors.size() - 1);
}

int GltfBuilder::add_vec3(const std::vector<glm::vec3>& values, bool bounds) {
  const int index =
      add_accessor(values.data(), values.size(), sizeof(glm::vec3), TINYGLTF_TYPE_VEC3,
                   TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TARGET_ARRAY_BUFFER);
  if (bounds) set_bounds<3>(model_.accessors.back(), values);
  return index;
}

int GltfBuilder::add_vec2(const std::vector<glm::vec2>& values) {
  return add_accessor(values.data(), values.size(), sizeof(glm::vec2), TINYGLTF_TYPE_VEC2,
                      TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TARGET_ARRAY_BUFFER);
}

int GltfBuilder::add_scalars(const std::vector<float>& values, bool bounds) {
  const int index = add_accessor(values.data(), values.size(), sizeof(float), TINYGLTF_TYPE_SCALAR,
                                 TINYGLTF_COMPONENT_TYPE_FLOAT, 0);
  if (bounds && !values.empty()) {
    const auto [lo, hi] = std::minmax_element(values.begin(), values.end());
    model_.accessors.back().minValues = {double(*lo)};
    model_.accessors.back().maxValues = {double(*hi)};
  }
  return index;
}

int GltfBuilder::add_indices(const std::vector<std::uint32_t>& indices) {
  return add_accessor(indices.data(), indices.size(), sizeof(std::uint32_t), TINYGLTF_TYPE_SCALAR,
                      TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
}

void GltfBuilder::set_mesh(const std::string& name, const tinygltf::Primitive& primitive,
                           const std::vector<double>& weights, const tinygltf::Value& extras) {
  tinygltf::Mesh mesh;
  mesh.name = name;
  mesh.primitives.push_back(primitive);
  mesh.weights = weights;
  mesh.extras = extras;
  model_.meshes = {mesh};
  tinygltf::Node node;
  node.name = name;
  node.mesh = 0;
  model_.nodes = {node};
  tinygltf::Scene scene;
  scene.nodes = {0};
  model_.scenes = {scene};
  model_.defaultScene = 0;
}

void GltfBuilder::add_animation(const tinygltf::Animation& animation) {
  model_.animations.push_back(animation);
}

void GltfBuilder::write_glb(const std::string& path) const {
  const std::string temporary = path + ".partial";
  {
    std::ofstream out(temporary, std::ios::binary);
    tinygltf::TinyGLTF writer;
    if (!out ||
        !writer.WriteGltfSceneToStream(&model_, out, /*prettyPrint=*/false,
                                       /*writeBinary=*/true) ||
        !out.flush()) {
      out.close();
      std::remove(temporary.c_str());
      throw Error(ErrorCode::kIo, "path", "'" + path + "': write failed");
    }
  }
  std::error_code ec;
  std::filesystem::rename(temporary, path, ec);
  if (ec) {
    std::remove(temporary.c_str());
    throw Error(ErrorCode::kIo, "path", "'" + path + "': " + ec.message());
  }
}

}  // namespace finflex::bake
