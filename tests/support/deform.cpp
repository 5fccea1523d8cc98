#include "support/deform.hpp"

#include "support/test_support.hpp"

namespace finflex::test {

RigParameters values_of(const RiggedMesh& model, const std::vector<float>& rows) {
  const std::size_t per = std::max<std::size_t>(model.values_per_instance(), 1);
  RigParameters values(model, rows.size() / per);
  values.values() = rows;
  return values;
}

DeformedBatch<float> run_on_device(ClDeformer& deformer, DeviceBatch& batch,
                                   const RigParameters& values, NormalMode normals, RigPath path,
                                   bool clamp) {
  ClJob job;
  job.model = &deformer.model();
  job.parameters = values.view();
  job.normals = normals;
  job.path = path;
  job.clamp = clamp;
  job.outputs = &batch;
  deformer.enqueue(job);
  return deformer.read(batch);
}

DeformedBatch<float> run_on_device(ClDeformer& deformer, const RigParameters& values,
                                   NormalMode normals, RigPath path, bool clamp,
                                   NormalFormat format) {
  DeviceBatch batch = deformer.allocate(values.instance_count(), format);
  return run_on_device(deformer, batch, values, normals, path, clamp);
}

RigParameters bend_fractions(const RiggedMesh& model, const std::vector<double>& fractions) {
  std::vector<float> m;
  for (double f : fractions) m.push_back(static_cast<float>(f * bend_limit(model)));
  return values_of(model, m);
}

double bend_limit(const RiggedMesh& model) { return model.rig().parameters.at(0).limit; }

}  // namespace finflex::test
