// The C++ library's answers for the Python tests: a job run through ClDeformer on the
// default device and through run_reference, written as raw arrays.
//
//   python_oracle MESH RIG|- rotate|jacobian INSTANCES VALUES OUT
// VALUES: INSTANCES x values_per_instance float32 (the rows). RIG "-": the exact single
// bend with the automatic frame. Writes OUT.device (float32) and OUT.reference
// (float64), each positions then normals as (instances, vertices, 3) in mesh order.
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include <finflex/finflex.hpp>

namespace {

template <typename T, typename Batch>
void write(const std::string& path, const Batch& batch) {
  std::vector<T> out;
  for (int attribute = 0; attribute < 2; ++attribute) {
    for (std::size_t i = 0; i < batch.layout.instance_count; ++i) {
      for (std::size_t v = 0; v < batch.layout.vertex_count; ++v) {
        const auto value = attribute == 0 ? batch.position(i, v) : batch.normal(i, v);
        for (int c = 0; c < 3; ++c) out.push_back(static_cast<T>(value[c]));
      }
    }
  }
  std::ofstream(path, std::ios::binary)
      .write(reinterpret_cast<const char*>(out.data()),
             static_cast<std::streamsize>(out.size() * sizeof(T)));
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 7) {
    std::fprintf(stderr, "usage: python_oracle MESH RIG|- rotate|jacobian INSTANCES VALUES OUT\n");
    return 2;
  }
  try {
    const finflex::Mesh mesh = finflex::load_mesh(argv[1]);
    const std::string rig = argv[2];
    const finflex::RiggedMesh model =
        rig == "-"
            ? finflex::RiggedMesh::single_bend(mesh, finflex::find_body_frame(mesh),
                                               finflex::BendMode::kExact)
            : finflex::RiggedMesh(mesh, finflex::resolve_rig(finflex::load_rig_file(rig), mesh));
    const finflex::NormalMode normals = finflex::parse_normal_mode(argv[3]);
    finflex::RigParameters values(model, std::stoul(argv[4]));
    std::ifstream(argv[5], std::ios::binary)
        .read(reinterpret_cast<char*>(values.values().data()),
              static_cast<std::streamsize>(values.values().size() * sizeof(float)));
    const std::string out = argv[6];

    finflex::Context context;
    finflex::ClDeformer deformer(context, model);
    finflex::DeviceBatch batch = deformer.allocate(values.instance_count());
    finflex::ClJob job;
    job.model = &model;
    job.parameters = values.view();
    job.normals = normals;
    job.outputs = &batch;
    deformer.enqueue(job);
    write<float>(out + ".device", deformer.read(batch));
    write<double>(out + ".reference", finflex::run_reference(model, values, normals));
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "python_oracle: %s\n", e.what());
    return 1;
  }
}
