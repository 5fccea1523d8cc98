// ClSwimDriver (finflex/cl_swim.hpp): the swim model's constants generated into the
// driver program (kernels/swim/driver.cl), per-fish state on the device.
#include "finflex/cl_swim.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <numeric>
#include <sstream>
#include <string>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif
// The staged inputs' check picks AVX2 at run time where the processor has it
// (GCC and Clang on x86).
#if defined(__GNUC__) && defined(__x86_64__)
#define FINFLEX_AVX2_CHECK 1
#include <immintrin.h>
#else
#define FINFLEX_AVX2_CHECK 0
#endif

#include "cl/device_buffers.hpp"
#include "cl/device_profile.hpp"
#include "cl/rig_source.hpp"
#include "cl/slot_layout.hpp"
#include "finflex/error.hpp"
#include "swim/kinematics.hpp"

namespace finflex {
namespace {

// A SwimInput as the kernel reads it: 7 floats (position, yaw, pitch, speed, turn rate).
constexpr std::size_t kInputFloats = 7;
static_assert(sizeof(SwimInput) == kInputFloats * sizeof(float),
              "SwimInput is uploaded as it is: 7 packed floats");

// Floats k to `count` of the inputs (k starts a whole input), one at a time: the end of
// copy_valid_inputs' pass, with what its blocks found (`carried`: the finiteness bits,
// `negative_speed`); true when all are valid.
bool scan_floats(const unsigned char* source, unsigned char* target, std::size_t k,
                 std::size_t count, std::uint32_t carried, std::uint32_t negative_speed) {
  for (; k < count; ++k) {
    std::uint32_t b;
    std::memcpy(&b, source + k * sizeof b, sizeof b);
    carried |= (b & 0x7f800000u) + 0x00800000u;
    if (k % kInputFloats == 5) {
      negative_speed |= (b >> 31) & static_cast<std::uint32_t>((b & 0x7fffffffu) != 0u);
    }
    if (target) std::memcpy(target + k * sizeof b, &b, sizeof b);
  }
  return ((carried >> 31) | negative_speed) == 0;
}

#if FINFLEX_AVX2_CHECK
bool has_avx2() {
  static const bool yes = __builtin_cpu_supports("avx2");
  return yes;
}

// copy_valid_inputs' check without a copy, 8 lanes wide: blocks of 8 inputs (56 floats
// in 7 vectors), whose speeds are floats 5, 12, ..., 54: one lane of each vector, two
// of the sixth: half the time of SSE2's in cache, alike when waiting on memory
// (docs/results/h100/swim_host_breakdown.txt).
__attribute__((target("avx2"))) bool valid_inputs_avx2(const SwimInput* inputs, std::size_t fish) {
  constexpr std::size_t kBlock = 8 * kInputFloats;
  const std::size_t count = fish * kInputFloats;
  const auto* source = reinterpret_cast<const unsigned char*>(inputs);
  const __m256i exponent = _mm256_set1_epi32(0x7f800000), one = _mm256_set1_epi32(0x00800000);
  const __m256i zero = _mm256_setzero_si256(), minus_zero = _mm256_set1_epi32(INT32_MIN);
  const __m256i speed_lanes[7] = {
      _mm256_setr_epi32(0, 0, 0, 0, 0, -1, 0, 0), _mm256_setr_epi32(0, 0, 0, 0, -1, 0, 0, 0),
      _mm256_setr_epi32(0, 0, 0, -1, 0, 0, 0, 0), _mm256_setr_epi32(0, 0, -1, 0, 0, 0, 0, 0),
      _mm256_setr_epi32(0, -1, 0, 0, 0, 0, 0, 0), _mm256_setr_epi32(-1, 0, 0, 0, 0, 0, 0, -1),
      _mm256_setr_epi32(0, 0, 0, 0, 0, 0, -1, 0)};
  __m256i carried8 = zero, negative8 = zero;
  std::size_t k = 0;
  for (; k + kBlock <= count; k += kBlock) {
    for (std::size_t v = 0; v < 7; ++v) {
      const __m256i b = _mm256_loadu_si256(
          reinterpret_cast<const __m256i*>(source + (k + 8 * v) * sizeof(float)));
      carried8 = _mm256_or_si256(carried8, _mm256_add_epi32(_mm256_and_si256(b, exponent), one));
      const __m256i below_zero =
          _mm256_andnot_si256(_mm256_cmpeq_epi32(b, minus_zero), _mm256_cmpgt_epi32(zero, b));
      negative8 = _mm256_or_si256(negative8, _mm256_and_si256(below_zero, speed_lanes[v]));
    }
  }
  std::uint32_t lanes[8], negative_lanes[8];
  _mm256_storeu_si256(reinterpret_cast<__m256i*>(lanes), carried8);
  _mm256_storeu_si256(reinterpret_cast<__m256i*>(negative_lanes), negative8);
  std::uint32_t carried = 0, negative_speed = 0;
  for (std::size_t j = 0; j < 8; ++j) {
    carried |= lanes[j];
    negative_speed |= negative_lanes[j] & 1u;
  }
  return scan_floats(source, nullptr, k, count, carried, negative_speed);
}
#endif

// Copies the inputs to the staging buffer (none when `staged` is null: the caller wrote
// them there, ClSwimDriver::staged_inputs); true when every value is finite and every
// speed >= 0, in one branch-free pass over the bits: a float is not finite when its
// exponent is all ones, which adding 1 to the exponent carries into bit 31; below 0
// when, as a 32-bit integer, it is negative and not -0 (INT32_MIN). The checks read the
// caller's floats, never the staging copy: staging memory the copy streamed to is slow
// to read back (docs/swimming.md, "Host time"). With SSE2 the copy streams past the
// caches (the host never reads the staging memory; a cached store would read each line
// first; docs/benchmarks.md#choice-staged-inputs).
bool copy_valid_inputs(const SwimInput* inputs, float* staged, std::size_t fish) {
#if FINFLEX_AVX2_CHECK
  if (staged == nullptr && has_avx2()) return valid_inputs_avx2(inputs, fish);
#endif
  const std::size_t count = fish * kInputFloats;
  const auto* source = reinterpret_cast<const unsigned char*>(inputs);
  auto* target = reinterpret_cast<unsigned char*>(staged);
  std::uint32_t carried = 0, negative_speed = 0;
  std::size_t k = 0;
#if defined(__SSE2__)
  if (reinterpret_cast<std::uintptr_t>(target) % 16 == 0) {
    // Blocks of 4 inputs, 28 floats in 7 vectors; the speeds (float 5 of each input)
    // are floats 5, 12, 19 and 26 of a block: these lanes of vectors 1, 3, 4 and 6.
    constexpr std::size_t kBlock = 4 * kInputFloats;
    const __m128i exponent = _mm_set1_epi32(0x7f800000), one = _mm_set1_epi32(0x00800000);
    const __m128i zero = _mm_setzero_si128(), minus_zero = _mm_set1_epi32(INT32_MIN);
    const __m128i speed_lanes[7] = {zero,
                                    _mm_setr_epi32(0, -1, 0, 0),
                                    zero,
                                    _mm_setr_epi32(-1, 0, 0, 0),
                                    _mm_setr_epi32(0, 0, 0, -1),
                                    zero,
                                    _mm_setr_epi32(0, 0, -1, 0)};
    __m128i carried4 = zero, negative4 = zero;
    for (; k + kBlock <= count; k += kBlock) {
      for (std::size_t v = 0; v < 7; ++v) {
        const std::size_t byte = (k + 4 * v) * sizeof(float);
        const __m128i b = _mm_loadu_si128(reinterpret_cast<const __m128i*>(source + byte));
        carried4 = _mm_or_si128(carried4, _mm_add_epi32(_mm_and_si128(b, exponent), one));
        const __m128i below_zero =
            _mm_andnot_si128(_mm_cmpeq_epi32(b, minus_zero), _mm_cmplt_epi32(b, zero));
        negative4 = _mm_or_si128(negative4, _mm_and_si128(below_zero, speed_lanes[v]));
        if (target) _mm_stream_si128(reinterpret_cast<__m128i*>(target + byte), b);
      }
    }
    if (target) _mm_sfence();  // the streamed stores reach memory before the upload reads it
    std::uint32_t lanes[4], negative_lanes[4];
    _mm_storeu_si128(reinterpret_cast<__m128i*>(lanes), carried4);
    _mm_storeu_si128(reinterpret_cast<__m128i*>(negative_lanes), negative4);
    carried = lanes[0] | lanes[1] | lanes[2] | lanes[3];
    negative_speed =
        (negative_lanes[0] | negative_lanes[1] | negative_lanes[2] | negative_lanes[3]) & 1u;
  }
#endif
  return scan_floats(source, target, k, count, carried, negative_speed);
}
// A float constant of the kernel, exactly as the host rounds the double (9 significant
// digits identify a float): the spine's constants then equal the stage table's bits.
std::string literal(double value) {
  std::ostringstream out;
  out.precision(9);
  out << std::scientific << static_cast<double>(static_cast<float>(value)) << "f";
  return out.str();
}

// The body's spine stage when it is the rig's only stage with derived values (so its
// records start each instance's derived row, kernels/rig.cl): the driver then writes
// them itself and the frame skips rig_prepare. Null otherwise.
const RigStage* driver_prepared_spine(const SwimModel& swim) {
  const Rig& rig = swim.model().rig();
  const RigStage* found = nullptr;
  std::size_t with_derived = 0;
  for (const RigComponent& component : rig.components) {
    for (const RigStage& stage : component.chain) {
      if (stage.deformer->derived_count == nullptr) continue;
      ++with_derived;
      if (&component == &rig.components.front() &&
          rig.parameters[stage.param].offset == swim.wave_offset()) {
        found = &stage;
      }
    }
  }
  return with_derived == 1 ? found : nullptr;
}

long offset_or_none(std::size_t offset) {
  return offset == SwimModel::kNone ? -1L : static_cast<long>(offset);
}

// The driver program's generated constants; `spine`: the stage whose records the
// driver writes (driver_prepared_spine), or null.
// `lanes`: fish per work-item (device_driver_lanes), `group`: work-items per group.
std::string driver_constants(const SwimModel& swim, std::size_t items, std::size_t lanes,
                             std::size_t group, const RigStage* spine) {
  const SwimKinematics& k = swim.kinematics();
  const RiggedMesh& model = swim.model();
  std::ostringstream out;
  out << "#define FF_LANES " << lanes << "\n"
      << "#define FF_SWIM_GROUP_SIZE " << group << "\n"
      << "#define FF_SWIM_ITEMS " << items << "\n"
      << detail::prepare_items_source(items) << "#define FF_SPINE_MAX_SAMPLES " << swim.samples()
      << "\n";
  // The spine's records (kernels/deformers/spine.cl, spine_records) from the stage
  // table's own constants (its sample count is FF_SWIM_SAMPLES).
  if (spine != nullptr) {
    const StageConstants c = spine->deformer->stage_constants(spine->options, spine->geometry);
    out << "#define FF_SWIM_DERIVED 1\n"
        << "#define FF_SWIM_DERIVED_COUNT " << detail::derived_per_instance(model.rig()) << "\n"
        << "#define FF_SWIM_SPINE_X_FIRST " << literal(c[0]) << "\n"
        << "#define FF_SWIM_SPINE_INVERSE_H " << literal(c[1]) << "\n"
        << "#define FF_SWIM_SPINE_H " << literal(c[2]) << "\n";
  } else {
    out << "#define FF_SWIM_DERIVED 0\n";
  }
  out << "#define FF_SWIM_SAMPLES " << swim.samples() << "\n"
      << "#define FF_SWIM_VALUES " << model.values_per_instance() << "\n"
      << "#define FF_SWIM_WAVE " << swim.wave_offset() << "\n"
      << "#define FF_SWIM_TAIL " << offset_or_none(swim.tail_offset()) << "\n"
      << "#define FF_SWIM_RIGHT " << offset_or_none(swim.right_pectoral_offset()) << "\n"
      << "#define FF_SWIM_LEFT " << offset_or_none(swim.left_pectoral_offset()) << "\n"
      << "#define FF_SWIM_X_FIRST " << literal(swim.sample_x(0)) << "\n"
      << "#define FF_SWIM_SPACING " << literal(swim.spacing()) << "\n"
      << "#define FF_SWIM_EXTENT " << literal(swim.x_snout() - swim.sample_x(0)) << "\n";
  const std::pair<const char*, double> kinematics[] = {
      {"FREQUENCY_SIZE", k.frequency_size},
      {"FREQUENCY_SPEED", k.frequency_speed},
      {"ENVELOPE0", k.envelope[0]},
      {"ENVELOPE1", k.envelope[1]},
      {"ENVELOPE2", k.envelope[2]},
      {"AMPLITUDE_BASE", k.amplitude_base},
      {"AMPLITUDE_SPEED", k.amplitude_speed},
      {"AMPLITUDE_MIN", k.amplitude_min},
      {"WAVELENGTH", k.wavelength},
      {"MAX_TURN_CURVATURE", k.max_turn_curvature},
      {"MIN_TURN_SPEED", k.min_turn_speed},
      {"CAUDAL_AMPLITUDE", k.caudal_amplitude},
      {"PEDUNCLE", k.peduncle},
      {"PECTORAL_REST", k.pectoral_rest},
      {"PECTORAL_AMPLITUDE", k.pectoral_amplitude},
      {"PECTORAL_HOVER_SPEED", k.pectoral_hover_speed}};
  for (const auto& [name, value] : kinematics)
    out << "#define FF_K_" << name << " " << literal(value) << "\n";
  auto table = [&](const char* name, const std::vector<double>& values) {
    out << "__constant float " << name << "[" << values.size() << "] = {";
    for (std::size_t j = 0; j < values.size(); ++j)
      out << (j ? ", " : "") << literal(std::min(values[j], 1e30));
    out << "};\n";
  };
  table("swim_max_positive", swim.max_bend_positive());
  table("swim_max_negative", swim.max_bend_negative());
  return out.str();
}

// The kernel indexes a fish's floats in 32-bit ints (kernels/swim/driver.cl: an index
// vector per lane on CPUs): `fish` fish whose widest row (the spine's records, the
// rig's values, the placement or the inputs) ends past INT32_MAX are refused, naming
// `lengths`, before anything is allocated.
void check_fish_count(const SwimModel& swim, std::size_t fish) {
  const std::size_t widest =
      std::max({kInputFloats, kPlacementFloats, swim.model().values_per_instance(),
                detail::derived_per_instance(swim.model().rig())});
  const std::size_t most = static_cast<std::size_t>(INT32_MAX) / widest;
  if (fish <= most) return;
  throw Error(ErrorCode::kInvalidArgument, "lengths",
              "lengths: " + std::to_string(fish) + " fish are more than one driver takes (" +
                  std::to_string(most) + " for this rig: " + std::to_string(widest) +
                  " floats a fish in its largest table); split them over several drivers");
}

}  // namespace

class ClSwimDriver::Impl {
 public:
  Impl(Context& context_in, const SwimModel& swim_in, const std::vector<float>& lengths,
       const std::vector<float>& phases, std::size_t items_per_fish)
      : context(context_in),
        swim(swim_in),
        fish(lengths.size()),
        items(detail::device_table_items(context_in.description(), swim_in.samples(),
                                         items_per_fish)),
        lanes(detail::device_driver_lanes(context_in.description(), items)),
        group(lanes > 1 ? detail::kLaneDriverGroupSize : detail::table_group_size(items)) {
    check_fish_count(swim, fish);
    SwimReference check(swim, lengths, phases);  // validates lengths and phases
    const cl::Context& cl_context = context.context();
    // Per fish its length and the size term of its tail-beat frequency
    // (kernels/swim/driver.cl's sizes): the cube root once, on the host.
    std::vector<float> sizes(2 * fish);
    for (std::size_t i = 0; i < fish; ++i) {
      sizes[2 * i] = lengths[i];
      sizes[2 * i + 1] =
          static_cast<float>(detail::tail_beat_frequency(swim.kinematics(), lengths[i], 0.0));
    }
    sizes_ = detail::make_buffer(cl_context, CL_MEM_READ_ONLY, sizes.size() * sizeof(float),
                                 sizes.data());
    std::vector<float> state(2 * fish);
    for (std::size_t i = 0; i < fish; ++i) {
      state[2 * i] = state[2 * i + 1] = static_cast<float>(check.wave_phases()[i]);
    }
    phases_ = detail::make_buffer(cl_context, CL_MEM_READ_WRITE, state.size() * sizeof(float),
                                  state.data());
    const std::vector<float> zeros(fish *
                                   std::max<std::size_t>(swim.model().values_per_instance(), 1));
    parameters_ = detail::make_buffer(cl_context, CL_MEM_READ_WRITE, zeros.size() * sizeof(float),
                                      zeros.data());
    placements_ =
        detail::make_buffer(cl_context, CL_MEM_READ_WRITE, fish * kPlacementFloats * sizeof(float));
    limited_ = detail::make_buffer(cl_context, CL_MEM_READ_WRITE, fish * sizeof(cl_uint));
    const RigStage* spine = driver_prepared_spine(swim);
    prepares_derived = spine != nullptr;
    // A placeholder float when the driver writes no records: the kernel takes the buffer.
    const std::size_t per_fish = detail::derived_per_instance(swim.model().rig());
    const std::size_t derived_floats =
        prepares_derived ? std::max<std::size_t>(fish * per_fish, 1) : 1;
    derived_ = detail::make_buffer(cl_context, CL_MEM_READ_WRITE, derived_floats * sizeof(float));
    // The spine's records come from kernels/deformers/spine.cl and what it builds on.
    const ProgramSource source{
        {"common/lanes.cl", "common/vec3.cl", "common/trig.cl", "common/scan.cl",
         "common/secant.cl", "common/stage_frame.cl", "deformers/spine.cl", "swim/driver.cl"},
        driver_constants(swim, items, lanes, group, spine),
        ""};
    kernel_ = context.kernel("swim_drive", source, "");
  }

  Context& context;
  const SwimModel& swim;
  std::size_t fish;
  std::size_t items;              // work-items per fish (swim/driver.cl's FF_SWIM_ITEMS)
  std::size_t lanes;              // fish per work-item (its FF_LANES)
  std::size_t group;              // work-items per group (its FF_SWIM_GROUP_SIZE)
  bool prepares_derived = false;  // the spine's records too (driver_prepared_spine)
  cl::Buffer derived_;
  cl::Buffer sizes_, phases_, parameters_, placements_, limited_;
  cl::Kernel kernel_;
  detail::ParameterUpload inputs_;
  SwimInput* staged_ = nullptr;  // the staging area staged_inputs() gave, until enqueued
  bool bound_ = false;
  float bound_dt_ = 0.0f;  // the kernel's dt argument (enqueue refuses dt <= 0)

  cl::Event upload_and_launch(float dt, const std::vector<cl::Event>* wait);
};

ClSwimDriver::ClSwimDriver(Context& context, const SwimModel& swim,
                           const std::vector<float>& lengths, const std::vector<float>& phases,
                           std::size_t items_per_fish)
    : impl_((detail::check_table_items(items_per_fish, "items_per_fish"),
             std::make_unique<Impl>(context, swim, lengths, phases, items_per_fish))) {}

ClSwimDriver::~ClSwimDriver() = default;

std::size_t ClSwimDriver::fish_count() const { return impl_->fish; }

cl::Event ClSwimDriver::enqueue(const std::vector<SwimInput>& inputs, float dt,
                                const std::vector<cl::Event>* wait) {
  Impl& d = *impl_;
  if (inputs.size() != d.fish || !std::isfinite(dt) || !(dt > 0.0f)) {
    check_swim_inputs(inputs, d.fish, dt);  // names the problem
  }
  // Copied as they are (the upload reads them after this returns), then checked in
  // one pass; only a bad value is looked for by name.
  float* staged = d.inputs_.acquire(d.context, d.fish * kInputFloats);
  d.staged_ = nullptr;  // a staged_inputs() area is this one, now overwritten
  if (!copy_valid_inputs(inputs.data(), staged, d.fish)) {
    check_swim_inputs(inputs, d.fish, dt);
  }
  return d.upload_and_launch(dt, wait);
}

SwimInput* ClSwimDriver::staged_inputs() {
  Impl& d = *impl_;
  if (!d.staged_) {
    // The ring's staging areas are mapped pinned memory, aligned for floats: a
    // SwimInput is 7 packed floats (kInputFloats).
    d.staged_ = reinterpret_cast<SwimInput*>(d.inputs_.acquire(d.context, d.fish * kInputFloats));
  }
  return d.staged_;
}

cl::Event ClSwimDriver::enqueue_staged(float dt, const std::vector<cl::Event>* wait) {
  Impl& d = *impl_;
  if (!d.staged_ && d.fish > 0) {
    throw Error(ErrorCode::kInvalidArgument, "staged_inputs",
                "staged_inputs: enqueue_staged() needs the inputs written into staged_inputs() "
                "first (none is staged since the last enqueue)");
  }
  // Checked where the caller wrote them; the area stays staged after a bad value, to be
  // mended and enqueued again.
  if (!std::isfinite(dt) || !(dt > 0.0f) ||
      (d.fish > 0 && !copy_valid_inputs(d.staged_, nullptr, d.fish))) {
    check_swim_inputs(d.staged_, d.fish, d.fish, dt);
  }
  d.staged_ = nullptr;
  return d.upload_and_launch(dt, wait);
}

// The staged inputs' upload after `wait`, then the driver kernel.
cl::Event ClSwimDriver::Impl::upload_and_launch(float dt, const std::vector<cl::Event>* wait) {
  Impl& d = *this;
  const bool replaced = d.inputs_.upload(d.context, wait);
  cl::Kernel& kernel = d.kernel_;
  if (replaced || !d.bound_) {
    cl_uint arg = 0;
    auto set = [&](const auto& value) { check_cl(kernel.setArg(arg++, value), "clSetKernelArg"); };
    set(d.inputs_.buffer());
    set(d.sizes_);
    set(d.phases_);
    set(d.parameters_);
    set(d.placements_);
    set(d.limited_);
    set(d.derived_);
    set(dt);
    set(static_cast<cl_uint>(d.fish));
    d.bound_ = true;
  } else if (dt != d.bound_dt_) {
    check_cl(kernel.setArg(7, dt), "clSetKernelArg dt");
  }
  d.bound_dt_ = dt;  // a steady frame rate sets no argument a frame
  cl::Event done;
  const std::size_t work_items = (d.fish * d.items + d.lanes - 1) / d.lanes;
  const std::size_t global = (work_items + d.group - 1) / d.group * d.group;
  check_cl(d.context.queue().enqueueNDRangeKernel(kernel, cl::NullRange, cl::NDRange(global),
                                                  cl::NDRange(d.group), nullptr, &done),
           "clEnqueueNDRangeKernel swim_drive");
  d.inputs_.used(done);
  return done;
}

const cl::Buffer& ClSwimDriver::parameter_buffer() const { return impl_->parameters_; }
const cl::Buffer& ClSwimDriver::placement_buffer() const { return impl_->placements_; }
const cl::Buffer* ClSwimDriver::derived_buffer() const {
  return impl_->prepares_derived ? &impl_->derived_ : nullptr;
}

RigParameters ClSwimDriver::read_parameters() {
  Impl& d = *impl_;
  RigParameters values(d.swim.model(), d.fish);
  if (!values.values().empty()) {
    check_cl(d.context.queue().enqueueReadBuffer(d.parameters_, CL_TRUE, 0,
                                                 values.values().size() * sizeof(float),
                                                 values.values().data()),
             "clEnqueueReadBuffer");
  }
  return values;
}

std::vector<float> ClSwimDriver::read_wave_phases() {
  Impl& d = *impl_;
  std::vector<float> state(2 * d.fish), phases(d.fish);
  check_cl(d.context.queue().enqueueReadBuffer(d.phases_, CL_TRUE, 0, state.size() * sizeof(float),
                                               state.data()),
           "clEnqueueReadBuffer");
  for (std::size_t i = 0; i < d.fish; ++i) phases[i] = state[2 * i];
  return phases;
}

std::vector<PlacementRecord> ClSwimDriver::read_placements() {
  Impl& d = *impl_;
  std::vector<PlacementRecord> records(d.fish);
  check_cl(d.context.queue().enqueueReadBuffer(d.placements_, CL_TRUE, 0,
                                               d.fish * sizeof(PlacementRecord), records.data()),
           "clEnqueueReadBuffer");
  return records;
}

std::size_t ClSwimDriver::read_limited_segments() {
  Impl& d = *impl_;
  std::vector<cl_uint> limited(d.fish);
  check_cl(d.context.queue().enqueueReadBuffer(d.limited_, CL_TRUE, 0, d.fish * sizeof(cl_uint),
                                               limited.data()),
           "clEnqueueReadBuffer");
  return std::accumulate(limited.begin(), limited.end(), std::size_t{0});
}

}  // namespace finflex
