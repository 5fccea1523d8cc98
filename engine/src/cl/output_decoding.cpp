#include "cl/output_decoding.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <vector>

#include "finflex/output_layout.hpp"

namespace finflex::detail {
namespace {

// IEEE 754 binary16 to float (every class handled).
float half_to_float(std::uint16_t h) {
  const std::uint32_t sign = static_cast<std::uint32_t>(h & 0x8000u) << 16;
  const std::uint32_t exponent = (h >> 10) & 0x1fu;
  const std::uint32_t mantissa = h & 0x3ffu;
  float magnitude;
  if (exponent == 0) {
    magnitude = std::ldexp(static_cast<float>(mantissa), -24);  // subnormal or zero
  } else if (exponent == 31) {
    magnitude =
        mantissa ? std::numeric_limits<float>::quiet_NaN() : std::numeric_limits<float>::infinity();
  } else {
    magnitude = std::ldexp(static_cast<float>(mantissa | 0x400u), static_cast<int>(exponent) - 25);
  }
  return sign ? -magnitude : magnitude;
}

float snorm16_to_float(std::int16_t s) { return std::max(float(s) / 32767.0f, -1.0f); }

// The octahedral decoding (docs/handoff.md gives it in GLSL).
glm::vec3 octahedral_to_vector(float u, float v) {
  glm::vec3 n(u, v, 1.0f - std::fabs(u) - std::fabs(v));
  const float t = std::max(-n.z, 0.0f);
  n.x += n.x >= 0.0f ? -t : t;
  n.y += n.y >= 0.0f ? -t : t;
  return glm::normalize(n);
}

// Element (i, v) of `a` from the raw bytes of its buffer.
glm::vec3 decode(const std::vector<unsigned char>& raw, const AttributeLayout& a, std::size_t i,
                 std::size_t v) {
  const std::size_t scalar = scalar_bytes(a.format);
  const bool packed = a.arrangement == Arrangement::kPacked;
  const std::size_t first =
      a.offset + i * a.instance_stride + (packed ? v * a.vertex_stride : v * scalar);
  const std::size_t apart = packed ? scalar : a.plane_stride * scalar;
  auto scalar_at = [&](std::size_t component, auto type) {
    decltype(type) value;
    std::memcpy(&value, raw.data() + first + component * apart, sizeof value);
    return value;
  };
  glm::vec3 out;
  switch (a.format) {
    case AttributeFormat::kFloat32x3:
    case AttributeFormat::kFloat32x4:
      for (int c = 0; c < 3; ++c) out[c] = scalar_at(std::size_t(c), float{});
      break;
    case AttributeFormat::kFloat16x3:
    case AttributeFormat::kFloat16x4:
      for (int c = 0; c < 3; ++c)
        out[c] = half_to_float(scalar_at(std::size_t(c), std::uint16_t{}));
      break;
    case AttributeFormat::kSnorm16x4:
      for (int c = 0; c < 3; ++c)
        out[c] = snorm16_to_float(scalar_at(std::size_t(c), std::int16_t{}));
      break;
    case AttributeFormat::kOctahedral16x2: {
      const std::uint32_t word = scalar_at(0, std::uint32_t{});
      out = octahedral_to_vector(snorm16_to_float(std::int16_t(word & 0xffffu)),
                                 snorm16_to_float(std::int16_t(word >> 16)));
      break;
    }
  }
  return out;
}

void read_attribute(Context& context, const cl::Buffer& buffer, const AttributeLayout& a,
                    const BatchShape& planes, std::size_t vertices, std::vector<float>& out) {
  std::vector<unsigned char> raw(OutputLayout::required_bytes(a, planes.instance_count, vertices));
  check_cl(context.queue().enqueueReadBuffer(buffer, CL_TRUE, 0, raw.size(), raw.data()),
           "clEnqueueReadBuffer outputs");
  for (std::size_t i = 0; i < planes.instance_count; ++i) {
    for (std::size_t v = 0; v < vertices; ++v) {
      const glm::vec3 value = decode(raw, a, i, v);
      for (int c = 0; c < 3; ++c) out[planes.index(i, c, v)] = value[c];
    }
  }
}

}  // namespace

DeformedBatch<float> read_outputs(Context& context, const DeviceBatch& batch,
                                  std::size_t vertices) {
  BatchShape planes = batch.shape;
  planes.plane_stride = vertices;
  planes.normal_format = NormalFormat::kFloat32;
  planes.tangents = batch.outputs.tangents.has_value();
  DeformedBatch<float> out;
  out.resize(planes);
  const OutputLayout& o = batch.outputs;
  read_attribute(context, batch.positions, o.positions, planes, vertices, out.positions);
  read_attribute(context, batch.normals, o.normals, planes, vertices, out.normals);
  if (o.tangents)
    read_attribute(context, batch.tangents, *o.tangents, planes, vertices, out.tangents);
  if (o.previous_positions) {
    out.previous_positions.assign(planes.attribute_elements(), 0.0f);
    read_attribute(context, batch.previous_positions, *o.previous_positions, planes, vertices,
                   out.previous_positions);
  }
  return out;
}

}  // namespace finflex::detail
