/* The planes' loads and stores of kernels/common/planes.cl for work-items of
 * FF_LANES > 1 lanes (kernels/common/lanes.cl): v is the work-item's first slot, a
 * multiple of FF_LANES, and component c of its lanes is the FF_LANES consecutive
 * floats from planes[(first_plane + c) * stride + v], loaded and stored as one vector.
 * Planes of float32 (the rest planes, the scratch sets and outputs in FinFlex's planes)
 * and of half (normals and tangents of NormalFormat::kHalf, store_half_lanes below):
 * kernels/cpu/lane_outputs.cl; any other output layout is stored lane by lane
 * (common/outputs.cl).
 *
 * Alignment: plane strides are multiples of 64 floats, so a work-item's lanes start
 * on a vector boundary of their plane; a plane is so aligned when its buffer is, as
 * buffers of the library's own always are (CL_DEVICE_MEM_BASE_ADDR_ALIGN, 128 bytes
 * on PoCL, covers the 64 of a float16 and the 128 of 32 lanes). The rest planes and
 * scratch sets are the library's own: loaded as aligned vectors. Outputs may be a
 * caller's buffers (PoCL uses a CL_MEM_USE_HOST_PTR buffer's memory as it is): each
 * store checks, and an unaligned plane is stored with vstoren.
 *
 * Build option FF_STREAMING_STORES (0/1, the host's choice: ClOptions::stores): 1,
 * aligned outputs are written with streaming (non-temporal) stores, which send whole
 * cache lines to memory without first reading them into the caches: an output of
 * thousands of fish larger than the caches would otherwise cost twice its bytes in
 * memory traffic; 0, ordinary stores (outputs that fit stay in the caches). */
#if FF_LANES > 1
#ifndef FF_STREAMING_STORES
#define FF_STREAMING_STORES 0
#endif

FF_INLINE LaneFloat load_lanes(__global const float* first) {
  return *(__global const LaneFloat*)first;
}

/* The same from an output plane, which may be a caller's and not aligned (vloadn); its
 * first `valid` lanes only (as the stores below), the others from `beyond`. */
FF_INLINE LaneFloat load_lanes_unaligned(__global const float* first, int valid, LaneFloat beyond) {
#if FF_LANES == 32
  if (valid < FF_LANES) {
    float kept[32];
    vstore16(beyond.lo, 0, kept);
    vstore16(beyond.hi, 0, kept + 16);
    for (int k = 0; k < valid; ++k) kept[k] = first[k];
    return (LaneFloat)(vload16(0, kept), vload16(0, kept + 16));
  }
  return (LaneFloat)(vload16(0, first), vload16(0, first + 16));
#else
  if (valid < FF_LANES) {
    float kept[FF_LANES];
    FF_VSTORE(beyond, 0, kept);
    for (int k = 0; k < valid; ++k) kept[k] = first[k];
    return FF_VLOAD(0, kept);
  }
  return FF_VLOAD(0, first);
#endif
}

/* The lanes of the work-item from slot v that hold output vertices: those before
 * FF_OUTPUT_LIMIT (mesh order of a model whose slots are its vertices; the kernels
 * store nothing for a work-item at or past it), else all. */
#ifdef FF_OUTPUT_LIMIT
#define FF_WRITES_LANES(v) ((v) < FF_OUTPUT_LIMIT)
#define FF_VALID_LANES(v) ((int)min((size_t)FF_LANES, (size_t)FF_OUTPUT_LIMIT - (v)))
#else
#define FF_WRITES_LANES(v) 1
#define FF_VALID_LANES(v) FF_LANES
#endif

/* A store is one native vector (StoreVector): 32 lanes store their two halves, each
 * streamed where it is aligned to its 64 bytes, so a caller's buffer aligned to 64
 * bytes takes streaming stores whatever the lanes. FF_STORE_VECTOR(type, first, value,
 * vstoren): the store of one vector of `type` at `first`. */
#if FF_LANES == 32
typedef float16 StoreVector;
#else
typedef LaneFloat StoreVector;
#endif

#if FF_STREAMING_STORES && defined(__clang__)
#define FF_STORE_ALIGNED(type, first, value) \
  __builtin_nontemporal_store(value, (__global type*)(first))
#else
#define FF_STORE_ALIGNED(type, first, value) (*(__global type*)(first) = (value))
#endif
#define FF_STORE_VECTOR(type, first, value, vstoren)        \
  if (((size_t)(first) & (sizeof(type) - 1)) == 0) {        \
    FF_STORE_ALIGNED(type, first, value);                   \
  } else {                                                  \
    vstoren(value, 0, first);                               \
  }

/* `valid`: the elements from `first` that are outputs (FF_OUTPUT_LIMIT: a work-item
 * that reaches past the last output vertex stores only its first ones, one by one;
 * elsewhere at least the vector's, which folds the test away). */
#define FF_STORE_VALID(type, element, first, value, valid, vstoren) \
  if ((valid) >= (int)(sizeof(type) / sizeof(element))) {           \
    FF_STORE_VECTOR(type, first, value, vstoren)                    \
  } else {                                                          \
    element kept[sizeof(type) / sizeof(element)];                   \
    vstoren(value, 0, kept);                                        \
    for (int k = 0; k < (valid); ++k) (first)[k] = kept[k];         \
  }

FF_INLINE void store_vector(__global float* first, StoreVector value, int valid) {
  FF_STORE_VALID(StoreVector, float, first, value, valid, FF_VSTORE)
}

FF_INLINE void store_lanes(__global float* first, LaneFloat value, int valid) {
#if FF_LANES == 32
  store_vector(first, value.lo, valid);
  store_vector(first + 16, value.hi, valid - 16);
#else
  store_vector(first, value, valid);
#endif
}

/* Half planes (normals and tangents of NormalFormat::kHalf): each lane's float as the
 * bits of the nearest half, rounded as the one-lane kernels round it
 * (common/planes.cl FF_DEFINE_HALF_BITS, on a vector of n lanes: the CPU's conversion
 * instruction where it has one, else integer operations that stay vector code), n
 * consecutive halves stored as one vector of ushorts. */
#define FF_DEFINE_HALF_STORE(n)                                                 \
  FF_DEFINE_HALF_BITS(n)                                                        \
  FF_INLINE void store_half_vector##n(__global ushort* first, float##n value,   \
                                      int valid) {                              \
    const ushort##n bits = half_bits##n(value);                                 \
    FF_STORE_VALID(ushort##n, ushort, first, bits, valid, vstore##n)            \
  }

#if FF_LANES == 8
FF_DEFINE_HALF_STORE(8)
#else
FF_DEFINE_HALF_STORE(16)
#endif

FF_INLINE void store_half_lanes(__global ushort* first, LaneFloat value, int valid) {
#if FF_LANES == 8
  store_half_vector8(first, value, valid);
#elif FF_LANES == 16
  store_half_vector16(first, value, valid);
#else
  store_half_vector16(first, value.lo, valid);
  store_half_vector16(first + 16, value.hi, valid - 16);
#endif
}

FF_INLINE Vec3 load_plane3(__global const float* planes, size_t first_plane, size_t stride,
                           size_t v) {
  return vec3(load_lanes(planes + first_plane * stride + v),
              load_lanes(planes + (first_plane + 1) * stride + v),
              load_lanes(planes + (first_plane + 2) * stride + v));
}

FF_INLINE void store_plane3(__global float* planes, size_t first_plane, size_t stride, size_t v,
                            Vec3 value) {
  store_lanes(planes + first_plane * stride + v, value.x, FF_LANES);
  store_lanes(planes + (first_plane + 1) * stride + v, value.y, FF_LANES);
  store_lanes(planes + (first_plane + 2) * stride + v, value.z, FF_LANES);
}
#endif
