// A small glTF 2.0 model builder over tinygltf for the bakes: one buffer, tightly
// packed float and index accessors (bounds where the specification wants them), one
// mesh, one node, one scene; written as a binary .glb whole or not at all.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <tiny_gltf.h>
#include <glm/glm.hpp>

namespace finflex::bake {

class GltfBuilder {
 public:
  GltfBuilder();

  // Accessors over copies of the values. `bounds`: write min and max (POSITION
  // accessors, morph targets' included, and animation inputs need them).
  int add_vec3(const std::vector<glm::vec3>& values, bool bounds);
  int add_vec2(const std::vector<glm::vec2>& values);
  int add_scalars(const std::vector<float>& values, bool bounds);  // no buffer target
  int add_indices(const std::vector<std::uint32_t>& indices);

  // The model's one mesh (one TRIANGLES primitive), on node 0 named `name` in scene 0.
  void set_mesh(const std::string& name, const tinygltf::Primitive& primitive,
                const std::vector<double>& weights = {},
                const tinygltf::Value& extras = tinygltf::Value());
  void add_animation(const tinygltf::Animation& animation);

  tinygltf::Model& model() { return model_; }
  // Writes a .glb through a temporary file renamed into place. finflex::Error kIo.
  void write_glb(const std::string& path) const;

 private:
  tinygltf::Model model_;
  int add_view(const void* bytes, std::size_t size, int target);
  int add_accessor(const void* bytes, std::size_t count, std::size_t element_bytes, int type,
                   int component_type, int target);
};

}  // namespace finflex::bake
