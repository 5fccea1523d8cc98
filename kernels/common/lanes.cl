/* Lanes: the vertex slots one work-item deforms. Build option FF_LANES (the host's
 * choice, finflex/cl_deformer.hpp ClOptions::lanes): 1 on GPUs, 8, 16 or 32 on CPUs.
 * Work-item w deforms the FF_LANES consecutive slots from w * FF_LANES, one in each
 * lane of an OpenCL vector, so a kernel of more than one lane is vector code by
 * construction: no compiler has to vectorise it across work-items (PoCL 3.1's
 * work-group vectoriser does that for the one-lane kernels, PoCL 5.0's does not:
 * docs/benchmarks.md).
 *
 * The per-vertex code (common/, deformers/) is written once, over LaneFloat and
 * LaneMask: float and int with one lane (the kernels are then the scalar ones,
 * token for token but for these names), float8/int8, float16/int16 or vectors of 32
 * with more.
 * What keeps one text right for both:
 *  - a comparison of lane values is a LaneMask (1 or 0 in a scalar, -1 or 0 in each
 *    lane of a vector); masks are combined only with & and |, and used only as the
 *    condition of ?:, which selects lane by lane;
 *  - a condition on values the same in every lane (a stage's constant) becomes a
 *    LaneMask through FF_UNIFORM_MASK;
 *  - both arms of a ?: on a LaneMask are LaneFloat (write constants as (LaneFloat)c);
 *  - values the same in every lane stay float (an instance's parameters, a stage's
 *    frame): OpenCL widens them where they meet lane values.
 * Planes are padded to 64 slots (finflex/batch.hpp), so the lanes of a work-item never
 * straddle two planes and their loads and stores are whole vectors
 * (kernels/cpu/lane_planes.cl). */
#ifndef FF_LANES
#define FF_LANES 1
#endif

#if FF_LANES == 1
typedef float LaneFloat;
typedef int LaneMask;
typedef int LaneInt;
#define FF_UNIFORM_MASK(condition) (condition)
#define FF_GATHER(base, index) ((base)[index])
#define FF_LANE_IDS 0
#elif FF_LANES == 8
typedef float8 LaneFloat;
typedef int8 LaneMask;
typedef int8 LaneInt;
#define FF_UNIFORM_MASK(condition) ((LaneMask)(-(int)(condition)))
#define FF_LANE_INT(x) convert_int8(x)
#define FF_LANE_FLOAT(x) convert_float8(x)
#define FF_VLOAD vload8
#define FF_VSTORE vstore8
#define FF_GATHER(base, index) FF_GATHER8(base, index)
#define FF_LANE_IDS ((int8)(0, 1, 2, 3, 4, 5, 6, 7))
#elif FF_LANES == 16
typedef float16 LaneFloat;
typedef int16 LaneMask;
typedef int16 LaneInt;
#define FF_UNIFORM_MASK(condition) ((LaneMask)(-(int)(condition)))
#define FF_LANE_INT(x) convert_int16(x)
#define FF_LANE_FLOAT(x) convert_float16(x)
#define FF_VLOAD vload16
#define FF_VSTORE vstore16
#define FF_GATHER(base, index) \
  ((float16)(FF_GATHER8(base, (index).lo), FF_GATHER8(base, (index).hi)))
#define FF_LANE_IDS ((int16)(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15))
#elif FF_LANES == 32
/* 32 lanes: a clang extended vector (OpenCL C has no vector of 32; the host asks for
 * it from PoCL only, engine/src/cl/device_profile.hpp). On AVX-512 each operation is two
 * independent ones on native vectors of 16: a work-item's long chain of dependent
 * steps becomes two side by side, which the processor overlaps. OpenCL's builtins have
 * no overloads for it: those the per-vertex code takes are added here, half by half.
 * No FF_LANE_IDS: its one user, the swim driver, takes one native vector. */
typedef float LaneFloat __attribute__((ext_vector_type(32)));
typedef int LaneMask __attribute__((ext_vector_type(32)));
typedef int LaneInt __attribute__((ext_vector_type(32)));
#define FF_UNIFORM_MASK(condition) ((LaneMask)(-(int)(condition)))
#define FF_LANE_INT(x) __builtin_convertvector((x), LaneInt)
#define FF_LANE_FLOAT(x) __builtin_convertvector((x), LaneFloat)
#define FF_VSTORE vstore16 /* of one half: kernels/cpu/lane_planes.cl */
#define FF_GATHER(base, index)                                                       \
  ((LaneFloat)(FF_GATHER8(base, (index).lo.lo), FF_GATHER8(base, (index).lo.hi),    \
               FF_GATHER8(base, (index).hi.lo), FF_GATHER8(base, (index).hi.hi)))
#define FF_LANE_UNARY(name)                                                          \
  inline LaneFloat __attribute__((overloadable)) name(LaneFloat a) {                 \
    return (LaneFloat)(name(a.lo), name(a.hi));                                      \
  }
#define FF_LANE_BINARY(name)                                                         \
  inline LaneFloat __attribute__((overloadable)) name(LaneFloat a, LaneFloat b) {    \
    return (LaneFloat)(name(a.lo, b.lo), name(a.hi, b.hi));                          \
  }                                                                                  \
  inline LaneFloat __attribute__((overloadable)) name(LaneFloat a, float b) {        \
    return (LaneFloat)(name(a.lo, b), name(a.hi, b));                                \
  }
FF_LANE_UNARY(fabs)
FF_LANE_UNARY(floor)
FF_LANE_UNARY(sqrt)
FF_LANE_UNARY(rsqrt)
FF_LANE_BINARY(fmin)
FF_LANE_BINARY(fmax)
inline LaneFloat __attribute__((overloadable)) clamp(LaneFloat a, float low, float high) {
  return (LaneFloat)(clamp(a.lo, low, high), clamp(a.hi, low, high));
}
#else
#error "FF_LANES must be 1, 8, 16 or 32"
#endif

/* The first slot of the work-item's lanes. */
#if FF_LANES == 1
#define FF_FIRST_SLOT get_global_id(0)
#else
#define FF_FIRST_SLOT (get_global_id(0) * FF_LANES)
#endif

/* FF_GATHER(base, index): base[index] lane by lane (index a LaneInt variable): a
 * vertex's own entry of a table, e.g. its spine segment's record, or an instance's
 * value when each lane is an instance (the swim driver's fish on CPUs). FF_LANE_IDS:
 * each lane's place, 0 to FF_LANES - 1. */
#define FF_GATHER8(base, index)                                                    \
  ((float8)((base)[(index).s0], (base)[(index).s1], (base)[(index).s2],            \
            (base)[(index).s3], (base)[(index).s4], (base)[(index).s5],            \
            (base)[(index).s6], (base)[(index).s7]))

/* The smallest and largest lanes of v, by halving: a few shuffles and comparisons
 * (all(v == v.s0) compiles to one extract and test per lane on PoCL). */
#if FF_LANES == 8
inline int2 lanes_range(int8 v) {
  const int4 low = min(v.lo, v.hi), high = max(v.lo, v.hi);
  const int2 low2 = min(low.lo, low.hi), high2 = max(high.lo, high.hi);
  return (int2)(min(low2.x, low2.y), max(high2.x, high2.y));
}
#elif FF_LANES == 16 || FF_LANES == 32
inline int2 lanes_range(LaneInt v) {
#if FF_LANES == 32
  const int16 low16 = min(v.lo, v.hi), high16 = max(v.lo, v.hi);
#else
  const int16 low16 = v, high16 = v;
#endif
  const int8 low = min(low16.lo, low16.hi), high = max(high16.lo, high16.hi);
  const int4 low4 = min(low.lo, low.hi), high4 = max(high.lo, high.hi);
  const int2 low2 = min(low4.lo, low4.hi), high2 = max(high4.lo, high4.hi);
  return (int2)(min(low2.x, low2.y), max(high2.x, high2.y));
}
#endif

/* The first and last lanes of a lane variable; lanes_ends: both, the smallest and the
 * largest where the lanes ascend. */
#if FF_LANES > 1
#define FF_FIRST_LANE(v) ((v).s0)
#if FF_LANES == 8
#define FF_LAST_LANE(v) ((v).s7)
#elif FF_LANES == 32
#define FF_LAST_LANE(v) ((v)[31])
#else
#define FF_LAST_LANE(v) ((v).sf)
#endif
inline int2 lanes_ends(LaneInt v) { return (int2)(FF_FIRST_LANE(v), FF_LAST_LANE(v)); }
#endif

/* base[index] = value lane by lane, in lane order (lanes with the same index must hold
 * the same value): an instance's own values where each lane is an instance;
 * lanes_scatter_count stores a count (a whole number held as a float) as a uint. */
#if FF_LANES == 1
inline void lanes_scatter(__global float* base, int index, float value) { base[index] = value; }
inline void lanes_scatter_count(__global uint* base, int index, float value) {
  base[index] = (uint)value;
}
#else
/* Lane `lane` of a LaneFloat or LaneInt variable, read through its memory. */
#define FF_FLOAT_LANE(v, lane) (((const float*)&(v))[lane])
#define FF_INT_LANE(v, lane) (((const int*)&(v))[lane])
inline void lanes_scatter(__global float* base, LaneInt index, LaneFloat value) {
  for (int lane = 0; lane < FF_LANES; ++lane)
    base[FF_INT_LANE(index, lane)] = FF_FLOAT_LANE(value, lane);
}
inline void lanes_scatter_count(__global uint* base, LaneInt index, LaneFloat value) {
  for (int lane = 0; lane < FF_LANES; ++lane)
    base[FF_INT_LANE(index, lane)] = (uint)FF_FLOAT_LANE(value, lane);
}
#endif
