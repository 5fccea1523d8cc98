// Output descriptors (finflex/output_layout.hpp) without a device: the size rule, and
// every rule of validate_output_layout with the field and the problem it names.
#include <gtest/gtest.h>

#include "finflex/finflex.hpp"
#include "support/throws_error.hpp"

namespace finflex {
namespace {

// A typical interleaved vertex: position float32x3 at 0, normal octahedral at 12,
// tangent snorm16x4 at 16, 24 bytes a vertex.
OutputLayout interleaved(std::size_t vertices) {
  OutputLayout layout;
  layout.positions = AttributeLayout::packed(AttributeFormat::kFloat32x3, vertices, 24, 0);
  layout.normals = AttributeLayout::packed(AttributeFormat::kOctahedral16x2, vertices, 24, 12);
  layout.tangents = AttributeLayout::packed(AttributeFormat::kSnorm16x4, vertices, 24, 16);
  return layout;
}

// The field and message of validate_output_layout's error ("" when it accepts).
std::pair<std::string, std::string> problem(const OutputLayout& layout, std::size_t instances,
                                            std::size_t vertices,
                                            const std::uintptr_t* ids = nullptr) {
  try {
    validate_output_layout(layout, instances, vertices, ids);
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::kInvalidArgument);
    return {e.field(), e.what()};
  }
  return {"", ""};
}

TEST(OutputLayout, RequiredBytesIsTheEndOfTheLastElement) {
  // Planes: instance 2's z plane ends the buffer.
  const AttributeLayout planes = AttributeLayout::planes(AttributeFormat::kFloat32x3, 128);
  EXPECT_EQ(planes.instance_stride, 3u * 128u * 4u);
  EXPECT_EQ(OutputLayout::required_bytes(planes, 3, 100), 2u * 1536u + (2u * 128u + 99u) * 4u + 4u);
  const AttributeLayout halves = AttributeLayout::planes(AttributeFormat::kFloat16x3, 64, 8);
  EXPECT_EQ(OutputLayout::required_bytes(halves, 1, 64), 8u + (2u * 64u + 63u) * 2u + 2u);
  // Packed: the last vertex of the last instance plus one element.
  const AttributeLayout packed = AttributeLayout::packed(AttributeFormat::kFloat32x4, 10, 32, 4);
  EXPECT_EQ(packed.instance_stride, 320u);
  EXPECT_EQ(OutputLayout::required_bytes(packed, 2, 10), 4u + 320u + 9u * 32u + 16u);
  EXPECT_EQ(format_bytes(AttributeFormat::kOctahedral16x2), 4u);
  EXPECT_EQ(scalar_bytes(AttributeFormat::kSnorm16x4), 2u);
}

TEST(OutputLayout, GoodLayoutsPass) {
  OutputLayout planes;
  planes.positions = AttributeLayout::planes(AttributeFormat::kFloat32x3, 64);
  planes.normals = AttributeLayout::planes(AttributeFormat::kFloat16x3, 64);
  EXPECT_EQ(problem(planes, 4, 64).first, "");
  EXPECT_EQ(problem(interleaved(100), 4, 100).first, "");
  const std::uintptr_t one_buffer[4] = {1, 1, 1, 2};
  EXPECT_EQ(problem(interleaved(100), 4, 100, one_buffer).first, "");
  // Instances side by side within each vertex (vertex-major).
  OutputLayout beside;
  beside.positions = AttributeLayout::packed(AttributeFormat::kFloat32x3, 50, 3 * 12, 0, 12);
  beside.normals = AttributeLayout::packed(AttributeFormat::kFloat32x3, 50);
  EXPECT_EQ(problem(beside, 3, 50).first, "");
  // Separate arrays in one buffer, one after the other.
  OutputLayout arrays;
  arrays.positions = AttributeLayout::packed(AttributeFormat::kFloat32x3, 50);
  arrays.normals = AttributeLayout::packed(AttributeFormat::kFloat16x4, 50, 0, 2 * 50 * 12);
  const std::uintptr_t shared[4] = {7, 7, 0, 0};
  EXPECT_EQ(problem(arrays, 2, 50, shared).first, "");
}

TEST(OutputLayout, EveryBrokenRuleIsNamed) {
  struct Case {
    const char* what;
    OutputLayout layout;
    std::string field;
    std::string words;
  };
  std::vector<Case> cases;
  {
    OutputLayout l = interleaved(10);
    l.positions.format = AttributeFormat::kSnorm16x4;
    cases.push_back({"position format", l, "outputs.positions.format", "not a position format"});
  }
  {
    OutputLayout l = interleaved(10);
    l.normals = AttributeLayout::planes(AttributeFormat::kOctahedral16x2, 16);
    cases.push_back({"planes format", l, "outputs.normals.format", "cannot be planes"});
  }
  {
    OutputLayout l = interleaved(10);
    l.normals.offset = 13;
    cases.push_back({"misaligned offset", l, "outputs.normals.offset", "not a multiple of 4"});
  }
  {
    OutputLayout l = interleaved(10);
    l.tangents->vertex_stride = 23;
    cases.push_back(
        {"misaligned stride", l, "outputs.tangents.vertex_stride", "not a multiple of 2"});
  }
  {
    OutputLayout l = interleaved(10);
    l.positions.vertex_stride = 8;
    cases.push_back({"stride below the element", l, "outputs.positions.vertex_stride",
                     "8 bytes is less than a float32x3 element (12 bytes)"});
  }
  {
    OutputLayout l = interleaved(10);
    l.normals.instance_stride = 24 * 9;
    cases.push_back({"instances overlap", l, "outputs.normals.instance_stride",
                     "overlaps the previous instance"});
  }
  {
    OutputLayout l = interleaved(10);
    l.positions = AttributeLayout::planes(AttributeFormat::kFloat32x3, 9);
    cases.push_back({"plane too short", l, "outputs.positions.plane_stride",
                     "9 elements is less than the 10 vertices"});
  }
  {
    OutputLayout l = interleaved(10);
    l.positions = AttributeLayout::planes(AttributeFormat::kFloat32x3, 16);
    l.positions.instance_stride = 100;
    cases.push_back({"planes overlap", l, "outputs.positions.instance_stride", "three planes"});
  }
  {
    OutputLayout l = interleaved(10);
    l.previous_positions = AttributeLayout::packed(AttributeFormat::kOctahedral16x2, 10);
    cases.push_back(
        {"previous format", l, "outputs.previous_positions.format", "not a position format"});
  }
  for (const Case& c : cases) {
    SCOPED_TRACE(c.what);
    const auto [field, message] = problem(c.layout, 3, 10);
    EXPECT_EQ(field, c.field);
    EXPECT_NE(message.find(c.words), std::string::npos) << message;
    EXPECT_EQ(message.rfind(c.field + ": ", 0), 0u) << message;
  }
  // Tangents not written: nothing of theirs to check.
  OutputLayout unused = interleaved(10);
  unused.tangents.reset();
  EXPECT_EQ(problem(unused, 3, 10).first, "");
}

TEST(OutputLayout, AttributesOfOneBufferMustNotShareBytes) {
  // Normals at 8 in a 24-byte vertex overlap the position's bytes 8-11.
  OutputLayout l = interleaved(10);
  l.normals.offset = 8;
  const std::uintptr_t one[4] = {1, 1, 1, 0};
  const auto [field, message] = problem(l, 2, 10, one);
  EXPECT_EQ(field, "outputs.normals");
  EXPECT_NE(message.find("shares bytes with outputs.positions"), std::string::npos) << message;
  // The same layout in separate buffers is fine: each buffer holds one attribute.
  const std::uintptr_t apart[4] = {1, 2, 3, 0};
  EXPECT_EQ(problem(l, 2, 10, apart).first, "");
  // Interleaved attributes with different strides are refused in one buffer.
  OutputLayout mixed = interleaved(10);
  mixed.tangents->vertex_stride = 26;
  mixed.tangents->instance_stride = 260;
  const auto refused = problem(mixed, 2, 10, one);
  EXPECT_EQ(refused.first, "outputs.tangents");
  // Previous positions over the positions' own bytes.
  OutputLayout previous = interleaved(10);
  previous.previous_positions = previous.positions;
  const std::uintptr_t same[4] = {1, 1, 1, 1};
  EXPECT_EQ(problem(previous, 2, 10, same).first, "outputs.previous_positions");
}

TEST(OutputLayout, FormatNamesRoundTrip) {
  for (AttributeFormat f : {AttributeFormat::kFloat32x3, AttributeFormat::kFloat32x4,
                            AttributeFormat::kFloat16x3, AttributeFormat::kFloat16x4,
                            AttributeFormat::kSnorm16x4, AttributeFormat::kOctahedral16x2}) {
    EXPECT_EQ(parse_attribute_format(to_string(f)), f);
  }
  try {
    parse_attribute_format("rgb565", "--normal-layout");
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.field(), "--normal-layout");
    EXPECT_NE(std::string(e.what()).find("'rgb565' is not a format"), std::string::npos);
  }
  for (VertexOrder order : {VertexOrder::kSlots, VertexOrder::kMesh}) {
    EXPECT_EQ(parse_vertex_order(to_string(order)), order);
  }
  for (Arrangement a : {Arrangement::kPlanes, Arrangement::kPacked}) {
    EXPECT_EQ(parse_arrangement(to_string(a)), a);
  }
  EXPECT_TRUE(test::ThrowsError([] { parse_vertex_order("columns"); }, ErrorCode::kInvalidArgument,
                                "order", "'columns' is not a vertex order"));
  EXPECT_TRUE(test::ThrowsError([] { parse_arrangement("rows", "outputs.normals.arrangement"); },
                                ErrorCode::kInvalidArgument, "outputs.normals.arrangement",
                                "'rows' is not an arrangement"));
}

TEST(OutputLayout, WrittenListsTheAttributesInTheKernelsOrder) {
  OutputLayout l = interleaved(10);
  auto written = l.written();
  EXPECT_EQ(written[0], &l.positions);
  EXPECT_EQ(written[1], &l.normals);
  EXPECT_EQ(written[2], &*l.tangents);
  EXPECT_EQ(written[3], nullptr);
  l.tangents.reset();
  l.previous_positions = l.positions;
  written = l.written();
  EXPECT_EQ(written[2], nullptr);
  EXPECT_EQ(written[3], &*l.previous_positions);
}

}  // namespace
}  // namespace finflex
