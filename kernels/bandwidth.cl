/* Reference kernels for the benchmarks: the same NDRange shape and output planes as
 * bend_batch (finflex/batch.hpp), with no arithmetic. write_planes gives the device's
 * write bandwidth; copy_rest reads the rest planes and writes them out per instance.
 * Written with scalar stores only, like bend_batch, so PoCL vectorises them alike;
 * write_planes honours FF_HALF_NORMALS and FF_INSTANCES_PER_ITEM as bend_batch does
 * (NDRange (plane_stride, ceil(instances / FF_INSTANCES_PER_ITEM))). */

__kernel void write_planes(__global float* restrict out_positions,
                           __global float* restrict out_normals, const uint stride,
                           const uint instances, const float value) {
  const size_t v = get_global_id(0);
  const size_t first_instance = get_global_id(1) * FF_INSTANCES_PER_ITEM;
  const Vec3 filler = vec3(value, value, value);
  for (uint k = 0; k < FF_INSTANCES_PER_ITEM; ++k) {
    const size_t instance = first_instance + k;
    if (instance >= instances) break;
    store_plane3(out_positions, instance * 3, stride, v, filler);
    store_direction3(out_normals, instance * 3, stride, v, filler); /* float32 or half */
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
