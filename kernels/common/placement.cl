/* World placement (finflex/placement.hpp) when FF_PLACEMENT is 1: per instance a
 * record of 16 floats, the columns of L Q (0-8: the orientation Q scaled by the fish's
 * length L), the position (9-11) and 1 / L (12). A vertex leaves the root's body frame
 * (lengths in body lengths) straight into the world:
 *   world(p) = position + L Q p,   world(d) = Q d = (L Q d) / L.
 * At a rig's last stage (the root's), this replaces leaving the frame to mesh
 * coordinates, so placing costs nothing more than not placing. */
#ifndef FF_PLACEMENT
#define FF_PLACEMENT 0
#endif

/* A record as the functions below read it. On GPUs with rotated normals a private
 * copy, read by FF_READ_PLACEMENT in four 16-byte loads (a record is 64 bytes and
 * starts on a multiple of 64 in its buffer, whose base the device aligns further)
 * instead of thirteen loads of one float: the loads a work-item issues, not the bytes,
 * cost there (10,000 swimming fish on an H200: 0.678 ms a frame's deformation against
 * 0.686, half normals 0.625 against 0.644). With Jacobian normals, whose
 * renormalisation holds more values, the copy held in registers throughout took 0.826
 * against 0.700: those read the record where it lies. Elsewhere the record where it
 * lies too (a CPU work-item's lanes share it: each float is loaded once and
 * broadcast). */
#if FF_GPU && !FF_NORMALS_JACOBIAN
typedef const float* PlacementRecord;
#define FF_READ_PLACEMENT(name, at)                                      \
  float name##_copy[16];                                                 \
  for (int quarter = 0; quarter < 4; ++quarter) {                       \
    vstore4(((__global const float4*)(at))[quarter], quarter, name##_copy); \
  }                                                                      \
  const PlacementRecord name = name##_copy;
#else
typedef __global const float* PlacementRecord;
#define FF_READ_PLACEMENT(name, at) const PlacementRecord name = (at);
#endif

FF_INLINE Vec3 place_linear(Vec3 v, PlacementRecord r) {
  return vec3(v.x * r[0] + v.y * r[3] + v.z * r[6], v.x * r[1] + v.y * r[4] + v.z * r[7],
              v.x * r[2] + v.y * r[5] + v.z * r[8]);
}

/* The position first, so that each coordinate is three multiply-adds. */
FF_INLINE Vec3 world_point(Vec3 p, PlacementRecord r) {
  return vec3(r[9] + p.x * r[0] + p.y * r[3] + p.z * r[6],
              r[10] + p.x * r[1] + p.y * r[4] + p.z * r[7],
              r[11] + p.x * r[2] + p.y * r[5] + p.z * r[8]);
}

FF_INLINE Vec3 world_direction(Vec3 d, PlacementRecord r) {
  const Vec3 turned = place_linear(d, r);
  const float inverse_length = r[12];
  return vec3(turned.x * inverse_length, turned.y * inverse_length, turned.z * inverse_length);
}

/* Places a vertex given in the root's body frame. */
FF_INLINE void place_local(Vec3* p, Vec3* n, Vec3* t, PlacementRecord r) {
  *p = world_point(*p, r);
  *n = world_direction(*n, r);
  *t = world_direction(*t, r);
}

/* Applies a stage's sample and leaves its frame (the root's body frame) for the world. */
FF_INLINE void leave_to_world(Vec3* p, Vec3* n, Vec3* t, PlacementRecord r, SecantSample s) {
  *p = world_point(secant_position(*p, s), r);
  *n = world_direction(secant_normal(*n, s), r);
  *t = world_direction(secant_tangent(*t, s), r);
}

/* In the rig kernels (variables p, n, t, source (the instance's inputs), stages and
 * placements in scope):
 *   FF_LEAVE_LAST(f, s)  the root's last stage leaves its frame: to the world when
 *                        placing, else to mesh coordinates;
 *   FF_PLACE_FROM_MESH   after a path that does not end at the root (a root without
 *                        stages), from mesh coordinates into the root's frame (its
 *                        row FF_ROOT_FRAME of the stage table) and to the world. */
#if FF_PLACEMENT
#define FF_LEAVE_LAST(f, s)                                     \
  {                                                             \
    FF_READ_PLACEMENT(record, placements + source * 16)       \
    leave_to_world(&p, &n, &t, record, s);                      \
  }
#else
#define FF_LEAVE_LAST(f, s) leave_frame(&p, &n, &t, f, s);
#endif
#if FF_PLACEMENT && defined(FF_ROOT_FRAME)
#define FF_PLACE_FROM_MESH                                   \
  {                                                          \
    const StageFrame root = ff_stage_table + FF_ROOT_FRAME;  \
    FF_READ_PLACEMENT(record, placements + source * 16)    \
    enter_frame(&p, &n, &t, root);                           \
    place_local(&p, &n, &t, record);                         \
  }
#else
#define FF_PLACE_FROM_MESH
#endif
