// The output layouts the benchmarks measure (finflex/output_layout.hpp, `finflex bench
// --layout`):
//   planes       FinFlex's structure-of-arrays planes (the default)
//   interleaved  one vertex struct: position float32x3, normal float32x3 (float16x4
//                with --normal-format half), tangent likewise
//   compact      position float32x3, normal and tangent octahedral16x2: 16 or 20 bytes
//   snorm        position float32x3, normal and tangent snorm16x4: 20 or 28 bytes
//   arrays       each attribute its own tightly packed array (glTF's accessors, a
//                renderer's separate vertex streams): position and normal float32x3
//                (normal float16x4 with --normal-format half), tangent float32x4
//                (float16x4)
// in slot or mesh order, with previous positions (float32x3 planes) when asked.
#pragma once

#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "finflex/finflex.hpp"

namespace finflex::bench {

enum class LayoutKind { kPlanes, kInterleaved, kCompact, kSnorm, kArrays };

// The layout's name as above ("planes", ...), and the layout of a name (none for
// another word).
const char* to_string(LayoutKind kind);
std::optional<LayoutKind> layout_named(const std::string& name);
// The names, for a message: "planes, interleaved, compact, snorm or arrays".
const char* layout_names();

// Where and how a benchmark's frames are written.
struct OutputsChoice {
  LayoutKind layout = LayoutKind::kPlanes;
  VertexOrder order = VertexOrder::kSlots;
  bool previous = false;  // previous positions too (float32x3 planes)
  bool host = false;      // in the caller's host memory (bind_host)
};

struct BenchLayout {
  OutputLayout layout;
  bool host = false;         // in the caller's host memory (bind_host)
  bool one_buffer = false;   // a vertex struct: every attribute in one buffer
  std::size_t vertices = 0;  // the outputs' vertex count (slots or mesh vertices)
};

BenchLayout bench_layout(const ClDeformer& deformer, NormalFormat format,
                         const OutputsChoice& choice);

// The caller's host memory of a --host batch: 64-byte aligned, one block per buffer.
struct HostMemory {
  std::vector<std::unique_ptr<unsigned char[], void (*)(void*)>> blocks;
};

// A batch in `layout`: vertex structs in one buffer, others one buffer per attribute; with
// layout.host over `memory` (ClDeformer::bind_host), else device buffers.
DeviceBatch make_bench_batch(ClDeformer& deformer, std::size_t instances, const BenchLayout& layout,
                             HostMemory& memory);

}  // namespace finflex::bench
