/* Shared by every FinFlex program: the inlining rule and the vector type.
 *
 * Every helper is inlined into its kernel: PoCL vectorises a kernel across work-items
 * only when no call is left in it. */
#define FF_INLINE inline __attribute__((always_inline))

/* Vectors are plain structs of scalars, not float3: once inlined they dissolve into
 * scalar registers, which lets PoCL vectorise across work-items (float3 operations
 * keep its loop vectoriser from doing so). Two unused floats make the struct larger
 * than 16 bytes: PoCL compiles for the host's calling convention, which passes
 * structs of up to 16 bytes as 2-float vectors, and such vectors, once formed, also
 * stop the vectoriser; larger structs dissolve into scalars. */
typedef struct {
  LaneFloat x, y, z; /* one vertex per lane (common/lanes.cl) */
  float unused0, unused1;
} Vec3;

FF_INLINE Vec3 vec3(LaneFloat x, LaneFloat y, LaneFloat z) {
  Vec3 v = {x, y, z, 0.0f, 0.0f};
  return v;
}

/* v / |v| without the library normalize()'s branches for huge and tiny vectors:
 * directions here are unit or of order 1. */
FF_INLINE Vec3 unit(Vec3 v) {
  const LaneFloat inverse_length = rsqrt(v.x * v.x + v.y * v.y + v.z * v.z);
  return vec3(v.x * inverse_length, v.y * inverse_length, v.z * inverse_length);
}
