// glTF 2.0 (.gltf) and GLB (.glb) writing through tinygltf: one mesh, one primitive,
// one node without transform; u32 indices; a .gltf holds its buffer as a base64 data
// URI, so the file stands alone.
#include <tiny_gltf.h>  // implementation compiled into libtinygltf (Debian package)

#include <cstdint>
#include <string>
#include <vector>

#include "finflex/error.hpp"
#include "io/formats.hpp"

namespace finflex::io {
namespace {

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
