#include "support/deform.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <string>

#include "support/test_support.hpp"

namespace finflex::test {

void expect_same_outputs(const DeformedBatch<float>& got, const DeformedBatch<float>& want) {
  EXPECT_EQ(got.positions, want.positions);
  EXPECT_EQ(got.normals, want.normals);
  EXPECT_EQ(got.tangents, want.tangents);
}

// The candidates are the halves around the value, found by scaling to the half's
// 11-bit significand (subnormal below 2^-14).
std::uint16_t nearest_half(float value) {
  const double v = std::fabs(static_cast<double>(value));
  const std::uint16_t sign = std::signbit(value) ? 0x8000 : 0;
  if (v == 0.0) return sign;
  if (std::isinf(v)) return sign | 0x7c00;
  const int exponent = v >= std::ldexp(1.0, -14) ? std::ilogb(v) : -15;  // -15: subnormal
  const double unit = exponent >= -14 ? std::ldexp(1.0, exponent - 10) : std::ldexp(1.0, -24);
  const double scaled = v / unit;  // exact: a power of two
  double lower = std::floor(scaled);
  const double above = scaled - lower;
  if (above > 0.5 || (above == 0.5 && std::fmod(lower, 2.0) != 0.0)) lower += 1.0;
  const double rounded = lower * unit;
  if (rounded >= 65536.0) return sign | 0x7c00;  // past the largest half, 65504: infinity
  if (rounded < std::ldexp(1.0, -14))
    return sign | static_cast<std::uint16_t>(rounded / std::ldexp(1.0, -24));
  const int e = std::ilogb(rounded);
  const auto fraction = static_cast<std::uint16_t>(rounded / std::ldexp(1.0, e - 10) - 1024.0);
  return sign | static_cast<std::uint16_t>((e + 15) << 10) | fraction;
}

RigParameters values_of(const RiggedMesh& model, const std::vector<float>& rows) {
  const std::size_t per = std::max<std::size_t>(model.values_per_instance(), 1);
  RigParameters values(model, rows.size() / per);
  values.values() = rows;
  return values;
}

DeformedBatch<float> run_on_device(ClDeformer& deformer, DeviceBatch& batch,
                                   const RigParameters& values, NormalMode normals, RigPath path,
                                   bool clamp, const Placement* placements) {
  ClJob job;
  job.instances = values.instance_count();
  job.parameters = values.view();
  job.normals = normals;
  job.path = path;
  job.clamp = clamp;
  job.placements = placements;
  job.outputs = &batch;
  deformer.enqueue(job);
  return deformer.read(batch);
}

DeformedBatch<float> run_on_device(ClDeformer& deformer, const RigParameters& values,
                                   NormalMode normals, RigPath path, bool clamp,
                                   NormalFormat format, const Placement* placements) {
  DeviceBatch batch = deformer.allocate(values.instance_count(), format);
  return run_on_device(deformer, batch, values, normals, path, clamp, placements);
}

RigParameters bend_fractions(const RiggedMesh& model, const std::vector<double>& fractions) {
  std::vector<float> m;
  for (double f : fractions) m.push_back(static_cast<float>(f * bend_limit(model)));
  return values_of(model, m);
}

double bend_limit(const RiggedMesh& model) { return model.rig().parameters.at(0).limit; }

RigParameters at_fractions_of_the_limits(const RiggedMesh& model,
                                         const std::vector<double>& fractions) {
  RigParameters values(model, fractions.size());
  const std::vector<RigParameter>& parameters = model.rig().parameters;
  for (std::size_t i = 0; i < fractions.size(); ++i) {
    for (std::size_t p = 0; p < parameters.size(); ++p) {
      for (std::size_t k = 0; k < parameters[p].count; ++k) {
        values.values()[i * values.values_per_instance() + parameters[p].offset + k] =
            static_cast<float>(fractions[i] * parameters[p].limit * (p % 2 ? -1.0 : 1.0));
      }
    }
  }
  std::vector<float> clamped(values.values().size());
  check_parameters(model.rig(), values.view(), /*clamp=*/true, clamped.data());
  values.values() = clamped;
  return values;
}

double expected_limit(const Mesh& mesh, const Rig& rig, std::size_t parameter) {
  const double pi = 3.14159265358979323846;
  double limit = INFINITY;
  for (std::size_t c = 0; c < rig.components.size(); ++c) {
    for (const RigStage& stage : rig.components[c].chain) {
      if (stage.param != parameter) continue;
      const std::string name = stage.deformer->name;
      if (name == "hinge") {
        limit = std::min(limit, pi);
      } else if (name == "bend") {
        double x_max = 0.0;
        for (std::size_t d = c; d < rig.subtree_end[c]; ++d) {
          for (std::uint32_t v : rig.components[d].vertices) {
            x_max = std::max(
                x_max, std::fabs(stage.frame.point_to_local(glm::dvec3(mesh.positions[v])).x));
          }
        }
        limit = std::min(limit, 0.5 / x_max);
      } else {
        ADD_FAILURE() << "no expected limit for the deformer " << name;
      }
    }
  }
  return limit;
}

void enqueue_copy(Context& context, const DeviceBatch& from, DeviceBatch& to) {
  const BatchShape& layout = from.shape;
  const std::size_t positions = layout.attribute_elements() * sizeof(float);
  const std::size_t directions = layout.attribute_elements() * layout.normal_component_bytes();
  cl::CommandQueue& queue = context.queue();
  check_cl(queue.enqueueCopyBuffer(from.positions, to.positions, 0, 0, positions),
           "clEnqueueCopyBuffer positions");
  check_cl(queue.enqueueCopyBuffer(from.normals, to.normals, 0, 0, directions),
           "clEnqueueCopyBuffer normals");
  if (layout.tangents) {
    check_cl(queue.enqueueCopyBuffer(from.tangents, to.tangents, 0, 0, directions),
             "clEnqueueCopyBuffer tangents");
  }
}

}  // namespace finflex::test
