#include "morph_animation.hpp"

#include <cstdio>

#include "gltf_builder.hpp"

namespace finflex::bake {

namespace {

std::vector<glm::vec3> positions(const DeformedBatch<float>& batch, std::size_t instance) {
  std::vector<glm::vec3> out(batch.shape.vertex_count);
  for (std::size_t v = 0; v < out.size(); ++v) out[v] = batch.position(instance, v);
  return out;
}

std::vector<glm::vec3> normals(const DeformedBatch<float>& batch, std::size_t instance) {
  std::vector<glm::vec3> out(batch.shape.vertex_count);
  for (std::size_t v = 0; v < out.size(); ++v) out[v] = batch.normal(instance, v);
  return out;
}

std::vector<glm::vec3> minus(std::vector<glm::vec3> a, const std::vector<glm::vec3>& b) {
  for (std::size_t v = 0; v < a.size(); ++v) a[v] -= b[v];
  return a;
}

}  // namespace

void write_morph_animation(const std::string& path, const std::string& name, const Mesh& mesh,
                           const BakedCycle& baked) {
  const std::size_t n = baked.cycle.frames;
  const std::vector<glm::vec3> rest_positions = positions(baked.batch, n);
  const std::vector<glm::vec3> rest_normals = normals(baked.batch, n);
  GltfBuilder gltf;
  tinygltf::Primitive primitive;
  primitive.mode = TINYGLTF_MODE_TRIANGLES;
  primitive.attributes["POSITION"] = gltf.add_vec3(rest_positions, /*bounds=*/true);
  primitive.attributes["NORMAL"] = gltf.add_vec3(rest_normals, false);
  if (!mesh.texcoords.empty()) primitive.attributes["TEXCOORD_0"] = gltf.add_vec2(mesh.texcoords);
  primitive.indices = gltf.add_indices(mesh.indices);
  tinygltf::Value::Array target_names;
  for (std::size_t k = 0; k < n; ++k) {
    std::map<std::string, int> target;
    target["POSITION"] = gltf.add_vec3(minus(positions(baked.batch, k), rest_positions), true);
    target["NORMAL"] = gltf.add_vec3(minus(normals(baked.batch, k), rest_normals), false);
    primitive.targets.push_back(target);
    char label[32];
    std::snprintf(label, sizeof label, "frame_%03zu", k);
    target_names.emplace_back(std::string(label));
  }
  tinygltf::Value::Object extras;
  extras["targetNames"] = tinygltf::Value(target_names);
  gltf.set_mesh(name, primitive, std::vector<double>(n, 0.0), tinygltf::Value(extras));

  // Keys 0 .. N at k T / N; key k (mod N) has weight 1 on target k.
  std::vector<float> times(n + 1);
  std::vector<float> weights((n + 1) * n, 0.0f);
  for (std::size_t k = 0; k <= n; ++k) {
    times[k] = static_cast<float>(double(k) * baked.cycle.dt_s);
    weights[k * n + k % n] = 1.0f;
  }
  tinygltf::AnimationSampler sampler;
  sampler.input = gltf.add_scalars(times, /*bounds=*/true);
  sampler.output = gltf.add_scalars(weights, false);
  sampler.interpolation = "LINEAR";
  tinygltf::AnimationChannel channel;
  channel.sampler = 0;
  channel.target_node = 0;
  channel.target_path = "weights";
  tinygltf::Animation animation;
  animation.name = "swim";
  animation.samplers.push_back(sampler);
  animation.channels.push_back(channel);
  gltf.add_animation(animation);
  gltf.write_glb(path);
}

}  // namespace finflex::bake
