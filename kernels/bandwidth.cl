/* Reference kernels for the benchmarks: the same NDRange shape and output planes as
 * bend_batch, with no arithmetic. write_planes gives the device's write bandwidth;
 * copy_rest reads the rest planes and writes them out per instance. */

__kernel void write_planes(__global float* restrict out_positions,
                         __global float* restrict out_normals, const uint stride,
                         const float value) {
  const size_t v = get_global_id(0);
  const size_t base = get_global_id(1) * 3 * (size_t)stride + v;
  for (int c = 0; c < 3; ++c) {
    out_positions[base + c * (size_t)stride] = value;
    out_normals[base + c * (size_t)stride] = value;
  }
}

__kernel void copy_rest(__global const float* restrict rest,
                        __global float* restrict out_positions,
                        __global float* restrict out_normals, const uint stride) {
  const size_t v = get_global_id(0);
  const size_t base = get_global_id(1) * 3 * (size_t)stride + v;
  for (int c = 0; c < 3; ++c) {
    out_positions[base + c * (size_t)stride] = rest[c * (size_t)stride + v];
    out_normals[base + c * (size_t)stride] = rest[(3 + c) * (size_t)stride + v];
  }
}
