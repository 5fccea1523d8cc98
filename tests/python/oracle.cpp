// The C++ library's answers for the Python tests: a job run through ClDeformer on the
// default device and through run_reference, written as raw arrays.
//
//   python_oracle MESH RIG|- rotate|jacobian INSTANCES VALUES OUT
//   python_oracle swim MESH RIG FRAMES LENGTHS INPUTS OUT   (swim() below)
// VALUES: INSTANCES x values_per_instance float32 (the rows). RIG "-": the exact single
// bend with the automatic frame. Writes OUT.device (float32) and OUT.reference
// (float64), each positions then normals as (instances, vertices, 3) in mesh order.
#include <algorithm>
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
    for (std::size_t i = 0; i < batch.shape.instance_count; ++i) {
      for (std::size_t v = 0; v < batch.shape.vertex_count; ++v) {
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

// python_oracle swim MESH RIG FRAMES LENGTHS INPUTS OUT: FRAMES frames of 1/30 s of
// ClSwimDriver (one fish per float32 of LENGTHS, the float32 (fish, 7) INPUTS every
// frame) and the placed deformation; writes OUT.device (positions then normals,
// float32, mesh order).
int swim(char** argv) {
  const finflex::Mesh mesh = finflex::load_mesh(argv[2]);
  const finflex::RiggedMesh model(mesh,
                                  finflex::resolve_rig(finflex::load_rig_file(argv[3]), mesh));
  const finflex::SwimModel swim_model(model);
  const unsigned long frames = std::stoul(argv[4]);
  auto read_floats = [](const char* path) {
    std::ifstream in(path, std::ios::binary | std::ios::ate);
    std::vector<float> values(static_cast<std::size_t>(in.tellg()) / sizeof(float));
    in.seekg(0);
    in.read(reinterpret_cast<char*>(values.data()),
            static_cast<std::streamsize>(values.size() * sizeof(float)));
    return values;
  };
  const std::vector<float> lengths = read_floats(argv[5]);
  const std::vector<float> rows = read_floats(argv[6]);
  std::vector<finflex::SwimInput> inputs;
  finflex::swim_inputs_from_rows(rows.data(), std::min(lengths.size(), rows.size() / 7), inputs);
  finflex::Context context;
  finflex::ClSwimDriver driver(context, swim_model, lengths);
  finflex::ClDeformer deformer(context, swim_model.model());
  finflex::DeviceBatch batch = deformer.allocate(lengths.size());
  finflex::ClJob job;
  job.instances = lengths.size();
  job.device.parameters = &driver.parameter_buffer();
  job.device.placements = &driver.placement_buffer();
  job.outputs = &batch;
  for (unsigned long f = 0; f < frames; ++f) {
    driver.enqueue(inputs, 1.0f / 30.0f);
    deformer.enqueue(job);
  }
  write<float>(std::string(argv[7]) + ".device", deformer.read(batch));
  return 0;
}

int main(int argc, char** argv) {
  if (argc == 8 && std::string(argv[1]) == "swim") {
    try {
      return swim(argv);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "python_oracle swim: %s\n", e.what());
      return 1;
    }
  }
  if (argc != 7) {
    std::fprintf(stderr,
                 "usage: python_oracle MESH RIG|- rotate|jacobian INSTANCES VALUES OUT\n"
                 "       python_oracle swim MESH RIG FRAMES LENGTHS INPUTS OUT\n");
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
    job.instances = values.instance_count();
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
