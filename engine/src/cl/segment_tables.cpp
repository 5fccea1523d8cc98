#include "cl/segment_tables.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace finflex::detail {
namespace {

constexpr std::size_t kSlots = 8;  // the fewest lanes a CPU kernel takes

// The entry of the 8 slots from `first` (of a component's [begin, end)) given each
// 8 slots' own segment (`block_segment`, -1 where they span more than one or leave the
// table): the segment, and bits 12, 13 and 14 where the 8, 16 or 32 slots from `first`
// share it.
std::uint32_t segment_entry(const std::vector<std::int32_t>& block_segment, std::size_t block,
                            std::size_t first, std::size_t end) {
  const std::int32_t s = block_segment[block];
  if (s < 0 || s > 0xfff) return 0u;
  std::uint32_t entry = static_cast<std::uint32_t>(s);
  for (std::size_t level = 0, count = kSlots; level < 3; ++level, count *= 2) {
    // The work-item of `count` lanes from `first`, within the component.
    if (first + count > end) break;
    const auto from = block_segment.begin() + static_cast<std::ptrdiff_t>(block);
    if (!std::all_of(from, from + static_cast<std::ptrdiff_t>(count / kSlots),
                     [s](std::int32_t other) { return other == s; })) {
      break;
    }
    entry |= 1u << (12 + level);
  }
  return entry;
}

// Entry `bin` of the 8 slots of `block`, from `first` of a component's [begin, end),
// from the lowest and highest position (x - x_0) / h each 8 slots reach in each bin,
// widened by a margin: the segment s the 8 slots' lowest lies in (bits 0-11), and bits
// 12, 13 and 14 set where the 8, 16 or 32 slots from `first` stay within s and the next
// segment, inside the table [0, last].
std::uint32_t swept_entry(const std::vector<double>& lowest, const std::vector<double>& highest,
                          std::size_t block, std::size_t bin, std::size_t first, std::size_t end,
                          double last) {
  // A hundredth of a segment: swept_segments' sampling, and the kernel's float rounding
  // of x and of the bin, move a vertex by far less.
  constexpr double kMargin = 0.01;
  const double low = lowest[block * kSweptBins + bin] - kMargin;
  if (!(low >= 0.0) || low >= 4096.0) return 0u;
  const double segment = std::floor(low);
  std::uint32_t entry = static_cast<std::uint32_t>(segment);
  for (std::size_t level = 0, count = kSlots; level < 3; ++level, count *= 2) {
    if (first + count > end) break;
    bool within = true;
    for (std::size_t b = block; b < block + count / kSlots; ++b) {
      within = within && lowest[b * kSweptBins + bin] - kMargin >= segment &&
               highest[b * kSweptBins + bin] + kMargin <= std::min(segment + 2.0, last);
    }
    if (!within) break;
    entry |= 1u << (12 + level);
  }
  return entry;
}

// The component's slot whose vertex slot `slot` holds: padding slots repeat the
// component's last vertex (make_rest_planes).
std::int64_t vertex_in_slot(const SlotLayout& slots, std::size_t begin, std::size_t slot) {
  for (std::size_t k = slot + 1; k-- > begin;) {
    if (slots.vertex_of_slot[k] >= 0) return slots.vertex_of_slot[k];
  }
  return -1;
}

// Program-scope constant array `name` of `type` under #if FF_LANES > 1, with `define`.
template <typename Entry>
std::string constant_table(const char* define, const char* type, const char* name,
                           const std::vector<Entry>& entries) {
  std::ostringstream out;
  out << "#if FF_LANES > 1\n#define " << define << " 1\n__constant " << type << " " << name << "["
      << entries.size() << "] = {" << std::hex;
  for (std::size_t i = 0; i < entries.size(); ++i)
    out << (i % 8 == 0 ? "\n  " : " ") << "0x" << entries[i] << "u,";
  out << "};\n#endif\n";
  return out.str();
}

}  // namespace

std::vector<std::uint32_t> slot_segments(const RiggedMesh& model, const SlotLayout& slots,
                                         const RestPlanes& rest) {
  const Rig& rig = model.rig();
  std::vector<std::uint32_t> table(slots.slot_count / kSlots, 0u);
  for (std::size_t c = 0; c < rig.components.size(); ++c) {
    const std::vector<StageRef>& path = model.paths()[c];
    if (path.empty()) continue;
    const RigStage& stage = rig.stage(path.front());
    if (!stage.deformer->rest_segments || stage.deformer->cl_rest_function == nullptr) continue;
    // The stage table's floats, and the kernel's float arithmetic (spine.cl spine_sample
    // and spine_at: the position, its segment within [0, last - 1] by truncation).
    const StageConstants k = stage.deformer->stage_constants(stage.options, stage.geometry);
    const float x_first = static_cast<float>(k[0]), inverse_h = static_cast<float>(k[1]);
    const float last = static_cast<float>(k[3]);
    // Each 8 slots' one segment, or -1.
    const std::size_t begin = slots.first_slot[c], end = slots.first_slot[c + 1];
    std::vector<std::int32_t> block_segment((end - begin) / kSlots, -1);
    for (std::size_t block = 0; block < block_segment.size(); ++block) {
      std::int32_t shared = -2;
      for (std::size_t slot = begin + block * kSlots; slot < begin + (block + 1) * kSlots; ++slot) {
        const float position = (rest.positions[slot] - x_first) * inverse_h;
        const std::int32_t s = position >= 0.0f && position <= last
                                   ? static_cast<std::int32_t>(std::min(position, last - 1.0f))
                                   : -1;
        shared = shared == -2 || shared == s ? s : -1;
      }
      block_segment[block] = shared;
    }
    for (std::size_t block = 0; block < block_segment.size(); ++block) {
      const std::size_t first = begin + block * kSlots;
      table[first / kSlots] = segment_entry(block_segment, block, first, end);
    }
  }
  return table;
}

SweptSegments swept_segments(const RiggedMesh& model, const SlotLayout& slots) {
  const Rig& rig = model.rig();
  SweptSegments swept;
  swept.first_entry.assign(rig.components.size(), SweptSegments::kNone);
  swept.limit.assign(rig.components.size(), 0.0);
  swept.mover_values.assign(rig.components.size(), 0);
  // Values sampled per bin: between samples a vertex's x stays within r d^2 / 8 of the
  // chord of its path (a circle's arc for the hinge), d the samples' spacing (at most
  // 2 kSweptRange / 256 = 0.00625 rad) and r the vertex's distance from the hinge:
  // 5e-6 r, which swept_entry's margin (a hundredth of a segment, 4e-5 body lengths
  // for a spine of 256 samples) covers. About 35 ms for the Blub's 2,240 fin slots on
  // one core, once per program.
  constexpr std::size_t kSamplesPerBin = 4;
  for (std::size_t c = 0; c < rig.components.size(); ++c) {
    const std::vector<StageRef>& path = model.paths()[c];
    if (path.size() != 2) continue;
    const RigStage& mover = rig.stage(path[0]);
    const RigStage& spine = rig.stage(path[1]);
    if (!spine.deformer->rest_segments || spine.deformer->cl_swept_function == nullptr) continue;
    const RigParameter& parameter = rig.parameters[mover.param];
    const double limit = std::min(parameter.limit, kSweptRange);
    if (parameter.count != 1 || !(limit > 0.0) || !std::isfinite(limit)) continue;
    const StageConstants k = spine.deformer->stage_constants(spine.options, spine.geometry);
    const double x_first = k[0], inverse_h = k[1], last = k[3];
    const std::size_t begin = slots.first_slot[c], end = slots.first_slot[c + 1];
    const std::size_t blocks = (end - begin) / kSlots;
    // The lowest and highest position (x - x_0) / h each 8 slots reach in each bin.
    std::vector<double> lowest(blocks * kSweptBins, std::numeric_limits<double>::infinity());
    std::vector<double> highest(blocks * kSweptBins, -std::numeric_limits<double>::infinity());
    const std::size_t samples = kSweptBins * kSamplesPerBin;
    const glm::dvec3 e_y(0.0, 1.0, 0.0);
    for (std::size_t slot = begin; slot < end; ++slot) {
      const std::int64_t v = vertex_in_slot(slots, begin, slot);
      if (v < 0) continue;
      const glm::dvec3 local = mover.frame.point_to_local(glm::dvec3(model.mesh().positions[v]));
      const std::size_t block = (slot - begin) / kSlots;
      for (std::size_t j = 0; j <= samples; ++j) {
        const double value = limit * (2.0 * double(j) / double(samples) - 1.0);
        // The mover's (7), p' = f(x, 0) + y e_y + z n, then the spine's x.
        const SecantSample s =
            mover.deformer->secant(local.x, &value, mover.options, mover.geometry);
        const glm::dvec3 moved = mover.frame.point_to_mesh(s.f + local.y * e_y + local.z * s.n);
        const double position = (spine.frame.point_to_local(moved).x - x_first) * inverse_h;
        // Sample j closes bin j / 4 - 1 and opens bin j / 4.
        for (const std::size_t bin :
             {j / kSamplesPerBin - (j % kSamplesPerBin == 0 ? 1 : 0), j / kSamplesPerBin}) {
          if (bin >= kSweptBins) continue;  // (the first's wraps when j = 0)
          double& low = lowest[block * kSweptBins + bin];
          double& high = highest[block * kSweptBins + bin];
          low = std::min(low, position);
          high = std::max(high, position);
        }
      }
    }
    swept.first_entry[c] = swept.entries.size();
    swept.limit[c] = limit;
    swept.mover_values[c] = parameter.offset;
    swept.entries.resize(swept.entries.size() + blocks * kSweptBins, 0u);
    for (std::size_t block = 0; block < blocks; ++block) {
      const std::size_t first = begin + block * kSlots;
      for (std::size_t bin = 0; bin < kSweptBins; ++bin) {
        swept.entries[swept.first_entry[c] + block * kSweptBins + bin] =
            static_cast<std::uint16_t>(swept_entry(lowest, highest, block, bin, first, end, last));
      }
    }
  }
  return swept;
}

std::string segment_tables_source(const std::vector<std::uint32_t>& slot_table,
                                  SweptSegments& swept) {
  // At most 2^15 entries each (the slot table 128 kB, its source about 400 kB: a CPU
  // deformer's one-lane programs, for layouts its lanes do not store, parse it too).
  constexpr std::size_t kMostEntries = std::size_t{1} << 15;
  auto worth = [](const auto& entries) {
    return entries.size() <= kMostEntries &&
           std::any_of(entries.begin(), entries.end(), [](auto entry) { return entry != 0u; });
  };
  std::string source;
  if (worth(slot_table)) {
    source += constant_table("FF_SLOT_SEGMENTS", "uint", "ff_slot_segments", slot_table);
  }
  if (worth(swept.entries)) {
    source += "#define FF_SWEPT_BINS " + std::to_string(kSweptBins) + "\n" +
              constant_table("FF_SWEPT_SEGMENTS", "ushort", "ff_swept_segments", swept.entries);
  } else {
    swept.entries.clear();
    std::fill(swept.first_entry.begin(), swept.first_entry.end(), SweptSegments::kNone);
  }
  return source;
}

std::string swept_arguments(const SweptSegments& swept, const SlotLayout& slots, std::size_t c) {
  // Entry (first slot / 8) * bins + bin of the kernel's work-item, from the component's.
  const long base = static_cast<long>(swept.first_entry[c]) -
                    static_cast<long>(slots.first_slot[c] / kSlots * kSweptBins);
  const float limit = static_cast<float>(swept.limit[c]);
  std::ostringstream out;
  out.precision(9);
  out << ", values[" << swept.mover_values[c] << "], " << base << ", " << std::scientific << limit
      << "f, " << static_cast<float>(double(kSweptBins) / (2.0 * double(limit))) << "f";
  return out.str();
}

}  // namespace finflex::detail
