/* Reference kernels for the benchmarks (not part of the library's programs): the same
 * NDRange shape and output planes as the deformation kernels (finflex/batch.hpp,
 * kernels/single_bend.cl, kernels/rig.cl), with no arithmetic. write_outputs gives the
 * device's write bandwidth for the batch's output layout; copy_rest reads rest planes
 * and writes them out per instance. Written with scalar stores only, like the
 * deformation kernels, so PoCL vectorises them alike; write_outputs honours the
 * output layout's options (kernels/common/outputs.cl), FF_INSTANCES_PER_ITEM and
 * FF_LANES (kernels/common/lanes.cl: vector stores of FF_LANES slots for FinFlex's
 * planes, vertex structs and attribute arrays, kernels/cpu/lane_outputs.cl, any other
 * layout lane by lane) as they do
 * (NDRange (output vertices / FF_LANES, ceil(instances / FF_INSTANCES_PER_ITEM))).
 * Mesh order is built as slot order with FF_OUTPUT_LIMIT = vertices (the host,
 * bench/support/reference_kernels.cpp): the first `vertices` places of each instance.
 * Built after the library's common kernel files.
 *
 * FF_VARYING_WRITES (0/1): write_outputs writes `value` everywhere (0), or values that
 * differ from vertex to vertex and instance to instance (1, a few integer operations):
 * GPUs may compress uniform data on its way to memory and so write it faster than
 * any real output could go. */
#ifndef FF_VARYING_WRITES
#define FF_VARYING_WRITES 0
#endif

/* Vertex structs of kernels of more than one lane (kernels/cpu/lane_outputs.cl): the
 * tangents' w as the one-slot stores below write it here. */
#ifdef FF_LANE_TANGENT_W
#undef FF_LANE_TANGENT_W
#define FF_LANE_TANGENT_W(v) ((LaneFloat)1.0f)
#endif

__kernel void write_outputs(FF_OUTPUT_ARGUMENTS, const uint vertices, const uint instances,
                            const float value) {
  FF_OUTPUT_LOCALS
  const size_t v = FF_FIRST_SLOT;
  const size_t first_instance = get_global_id(1) * FF_INSTANCES_PER_ITEM;
  for (uint k = 0; k < FF_INSTANCES_PER_ITEM; ++k) {
    const size_t instance = first_instance + k;
    if (instance >= instances) break;
#if FF_VARYING_WRITES
    /* A float in [value, 2 value) (value a power of two) with hashed mantissa bits. */
    const uint bits = ((uint)v * 2654435761u) ^ ((uint)instance * 40503u);
    const float varied = as_float(as_uint(value) | (bits >> 9));
    const Vec3 filler = vec3(varied, varied, varied);
#else
    const Vec3 filler = vec3(value, value, value);
#endif
    /* Every output as the deformation kernels store it (common/outputs.cl); places at
     * or past `vertices` (mesh order's padding) write nothing. */
#if FF_STAGED_STRUCT || ((FF_LANE_PLANES || FF_LANE_STRUCT || FF_LANE_ARRAYS) && FF_LANES > 1)
    {
      const Vec3 p = filler, n = filler, t = filler;
      FF_STORE_OUTPUTS(instance, v)
    }
#elif FF_LANES == 1
    if (v < vertices) {
      store_outputs(out_positions, out_normals, out_tangents, out_previous, out_layout, instance,
                    v, filler, filler, filler, 1.0f);
    }
#else
    for (int lane = 0; lane < FF_LANES; ++lane) {
      if (v + lane < vertices) {
        const StoreVec3 one = lane_of(filler, lane);
        store_outputs(out_positions, out_normals, out_tangents, out_previous, out_layout,
                      instance, v + lane, one, one, one, 1.0f);
      }
    }
#endif
  }
}

__kernel void copy_rest(__global const float* restrict rest,
                        __global float* restrict out_positions,
                        __global float* restrict out_normals, const uint stride) {
  const size_t v = get_global_id(0);
  const size_t base = get_global_id(1) * 3 * (size_t)stride + v;
  out_positions[base] = rest[v];
  out_positions[base + stride] = rest[stride + v];
  out_positions[base + 2 * (size_t)stride] = rest[2 * (size_t)stride + v];
  out_normals[base] = rest[3 * (size_t)stride + v];
  out_normals[base + stride] = rest[4 * (size_t)stride + v];
  out_normals[base + 2 * (size_t)stride] = rest[5 * (size_t)stride + v];
}
