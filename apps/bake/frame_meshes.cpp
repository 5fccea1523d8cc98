#include "frame_meshes.hpp"

#include <cstdio>
#include <filesystem>

#include "finflex/instance_mesh.hpp"
#include "finflex/mesh_io.hpp"

namespace finflex::bake {

void write_frame_meshes(const std::string& folder, const std::string& stem,
                        const std::string& extension, const Mesh& mesh, const BakedCycle& baked) {
  Mesh rest = mesh;
  rest.tangents.clear();  // the frames carry positions and normals only
  for (std::size_t k = 0; k < baked.cycle.frames; ++k) {
    char name[32];
    std::snprintf(name, sizeof name, "_frame_%03zu.", k);
    const std::string path = (std::filesystem::path(folder) / (stem + name + extension)).string();
    save_mesh(path, instance_mesh(rest, baked.batch, k));
  }
}

}  // namespace finflex::bake
