/* Structure-of-arrays planes (finflex/batch.hpp): component c of vertex v of an
 * array whose planes start at `first_plane` is planes[(first_plane + c) * stride + v]. */

FF_INLINE Vec3 load_plane3(__global const float* planes, size_t first_plane, size_t stride,
                        size_t v) {
  return vec3(planes[first_plane * stride + v], planes[(first_plane + 1) * stride + v],
              planes[(first_plane + 2) * stride + v]);
}

FF_INLINE void store_plane3(__global float* planes, size_t first_plane, size_t stride, size_t v,
                         Vec3 value) {
  planes[first_plane * stride + v] = value.x;
  planes[(first_plane + 1) * stride + v] = value.y;
  planes[(first_plane + 2) * stride + v] = value.z;
}

