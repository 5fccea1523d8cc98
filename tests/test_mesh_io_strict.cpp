// Hostile and malformed input to load_mesh: every file comes back with exactly the
// vertices and faces it holds or fails with an error naming the line or element and
// the reason; declared counts are checked against the bytes present before anything
// is allocated; glTF scene graphs are walked once, without recursion; only regular
// files are read.
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <future>
#include <limits>
#include <new>
#include <string>
#include <vector>

#include "finflex/error.hpp"
#include "finflex/mesh.hpp"
#include "finflex/mesh_io.hpp"
#include "support/test_support.hpp"
#include "support/throws_error.hpp"

// ---------------------------------------------------------------------------------
// Allocation probe: while active, records the largest single allocation and refuses
// any above kAllocationCap (so a reader that trusts a declared count fails fast
// instead of exhausting the machine).

namespace {

std::atomic<bool> g_probe_active{false};
std::atomic<std::size_t> g_largest_allocation{0};
constexpr std::size_t kAllocationCap = std::size_t{1} << 30;

void* allocate(std::size_t size) {
  if (g_probe_active.load(std::memory_order_relaxed)) {
    std::size_t seen = g_largest_allocation.load(std::memory_order_relaxed);
    while (size > seen && !g_largest_allocation.compare_exchange_weak(seen, size)) {
    }
    if (size > kAllocationCap) throw std::bad_alloc();
  }
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}

}  // namespace

void* operator new(std::size_t size) { return allocate(size); }
void* operator new[](std::size_t size) { return allocate(size); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }

namespace finflex {
namespace {

namespace fs = std::filesystem;
using test::data_path;
using test::temp_path;
using test::ThrowsError;

// The largest single allocation `action` makes (exceptions are swallowed).
std::size_t largest_allocation(const std::function<void()>& action) {
  g_largest_allocation = 0;
  g_probe_active = true;
  try {
    action();
  } catch (...) {
  }
  g_probe_active = false;
  return g_largest_allocation;
}

// ThrowsError for load_mesh(path), also checking that the message starts with the
// quoted path.
::testing::AssertionResult LoadFails(const std::string& path, ErrorCode code,
                                     const std::string& field_part,
                                     const std::vector<std::string>& message_parts = {}) {
  std::vector<std::string> parts = message_parts;
  parts.push_back("'" + path + "': ");
  ::testing::AssertionResult result =
      ThrowsError([&] { load_mesh(path); }, code, field_part, parts);
  if (!result) return result;
  try {
    load_mesh(path);
  } catch (const Error& e) {
    if (std::string(e.what()).rfind("'" + path + "': ", 0) != 0) {
      return ::testing::AssertionFailure() << "message does not start with the path: " << e.what();
    }
  }
  return result;
}

void write_file(const std::string& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary);
  out << bytes;
  ASSERT_TRUE(out.good()) << path;
}

std::string write_and_return(const std::string& path, const std::string& bytes) {
  write_file(path, bytes);
  return path;
}

// `bytes` written to a fresh file named `name`; returns its path.
std::string file_with(const std::string& name, const std::string& bytes) {
  const std::string path = temp_path(name);
  write_file(path, bytes);
  return path;
}

template <typename T>
void append(std::string& out, const T& value) {
  out.append(reinterpret_cast<const char*>(&value), sizeof value);
}

template <typename T>
void append_big_endian(std::string& out, const T& value) {
  char bytes[sizeof value];
  std::memcpy(bytes, &value, sizeof value);
  for (std::size_t i = sizeof value; i > 0; --i) out += bytes[i - 1];
}

// Runs `action` on another thread; fails if it has not finished after `seconds`, and
// then calls `unblock` so that the thread can end.
::testing::AssertionResult FinishesWithin(int seconds, const std::function<void()>& action,
                                          const std::function<void()>& unblock) {
  std::future<void> done = std::async(std::launch::async, action);
  if (done.wait_for(std::chrono::seconds(seconds)) == std::future_status::ready) {
    return ::testing::AssertionSuccess();
  }
  unblock();
  done.wait();
  return ::testing::AssertionFailure() << "still running after " << seconds << " s";
}

// Opens and closes the write end of the FIFO `path`, releasing a reader blocked on it.
void release_fifo_reader(const std::string& path) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_NONBLOCK);
  if (fd >= 0) ::close(fd);
}

const std::string kFourVertices = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\n";

// ---------------------------------------------------------------------------------
// OBJ

struct BadNumber {
  const char* token;
  ErrorCode code;
  const char* reason;
};

class ObjBadVertexNumber : public ::testing::TestWithParam<BadNumber> {};

// OpenMesh dropped such "v" lines and renumbered the vertices after them: the mesh
// loaded with a vertex less and every face shifted onto other vertices.
TEST_P(ObjBadVertexNumber, FailsNamingTheLineAndTheToken) {
  const BadNumber bad = GetParam();
  const std::string path = file_with("bad_vertex.obj", "v 0 0 0\nv 1 " + std::string(bad.token) +
                                                           " 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\n");
  EXPECT_TRUE(LoadFails(path, bad.code, "line 2",
                        {"line 2: 'v' y '" + std::string(bad.token) + "' " + bad.reason}));
}

INSTANTIATE_TEST_SUITE_P(
    Tokens, ObjBadVertexNumber,
    ::testing::Values(BadNumber{"nan", ErrorCode::kInvalidMesh, "is not finite"},
                      BadNumber{"-inf", ErrorCode::kInvalidMesh, "is not finite"},
                      BadNumber{"infinity", ErrorCode::kInvalidMesh, "is not finite"},
                      BadNumber{"1e999", ErrorCode::kInvalidMesh, "is outside the float range"},
                      BadNumber{"-3.5e39", ErrorCode::kInvalidMesh, "is outside the float range"},
                      BadNumber{"abc", ErrorCode::kFormat, "is not a number"},
                      BadNumber{"1.5.2", ErrorCode::kFormat, "is not a number"},
                      BadNumber{"0x10", ErrorCode::kFormat, "is not a number"},
                      BadNumber{"1,5", ErrorCode::kFormat, "is not a number"},
                      BadNumber{"+-1", ErrorCode::kFormat, "is not a number"}));

TEST(ObjStrict, AnUnreadableVertexIsNotReportedAsAFaceIndexOutOfRange) {
  const std::string path = file_with("unreadable.obj", "v 0 0 0\nv 1 0 0\nv 0 abc 0\nf 1 2 3\n");
  EXPECT_TRUE(
      LoadFails(path, ErrorCode::kFormat, "line 3", {"line 3: 'v' y 'abc' is not a number"}));
  try {
    load_mesh(path);
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()).find("out of range"), std::string::npos) << e.what();
  }
}

TEST(ObjStrict, NumbersAtTheEdgesOfTheFloatRange) {
  // FLT_MAX, a number just above it that rounds to it, an underflow that rounds to 0
  // and a subnormal: all readable floats.
  const std::string path = file_with(
      "edges.obj", "v 3.40282347e38 3.4028235e38 1e-50\nv 1e-45 -0 +2\nv 0 1 0\nf 1 2 3\n");
  const Mesh mesh = load_mesh(path);
  ASSERT_EQ(mesh.vertex_count(), 3u);
  EXPECT_EQ(mesh.positions[0].x, std::numeric_limits<float>::max());
  EXPECT_EQ(mesh.positions[0].y, std::numeric_limits<float>::max());
  EXPECT_EQ(mesh.positions[0].z, 0.0f);
  EXPECT_EQ(mesh.positions[1].x, std::numeric_limits<float>::denorm_min());
  EXPECT_EQ(mesh.positions[1].z, 2.0f);
}

struct BadFace {
  const char* face;
  ErrorCode code;
  const char* message;
};

class ObjBadFace : public ::testing::TestWithParam<BadFace> {};

// OpenMesh dropped every one of these faces and loaded the rest.
TEST_P(ObjBadFace, FailsNamingTheLine) {
  const BadFace bad = GetParam();
  const std::string path =
      file_with("bad_face.obj", kFourVertices + "f " + bad.face + "\nf 1 2 3\n");
  EXPECT_TRUE(LoadFails(path, bad.code, "line 5", {std::string("line 5: ") + bad.message}));
}

INSTANTIATE_TEST_SUITE_P(
    Faces, ObjBadFace,
    ::testing::Values(
        BadFace{"1 2 x", ErrorCode::kFormat, "face corner 3: v index 'x' is not an integer"},
        BadFace{"1 2 1.5", ErrorCode::kFormat, "face corner 3: v index '1.5' is not an integer"},
        BadFace{"1 2 99999", ErrorCode::kInvalidMesh,
                "face corner 3: v index 99999 is out of range (4 'v' lines in the file)"},
        // Wraps to 2 in 32 bits.
        BadFace{"1 3 4294967298", ErrorCode::kInvalidMesh,
                "face corner 3: v index 4294967298 is out of range"},
        BadFace{"1 2 99999999999999999999", ErrorCode::kInvalidMesh,
                "face corner 3: v index '99999999999999999999' is out of range"},
        BadFace{"1 2 0", ErrorCode::kInvalidMesh, "face corner 3: v index 0 is out of range"},
        BadFace{"1 2 -9", ErrorCode::kInvalidMesh,
                "face corner 3: v index -9 is out of range (4 'v' lines before it)"},
        BadFace{"1 2", ErrorCode::kFormat, "face has 2 corners, at least 3 needed"},
        BadFace{"1 1 2", ErrorCode::kInvalidMesh,
                "face uses vertex 1 at corners 1 and 2 (a polygon's corners must be distinct)"},
        BadFace{"1 2 3 -2", ErrorCode::kInvalidMesh, "face uses vertex 3 at corners 3 and 4"},
        BadFace{"1 2 3/7", ErrorCode::kInvalidMesh,
                "face corner 3: vt index 7 is out of range (0 'vt' lines in the file)"},
        BadFace{"1 2 3//9", ErrorCode::kInvalidMesh,
                "face corner 3: vn index 9 is out of range (0 'vn' lines in the file)"},
        BadFace{"1 2 3/", ErrorCode::kFormat,
                "face corner 3 '3/' is not v, v/vt, v//vn or v/vt/vn"},
        BadFace{"1 2 /3", ErrorCode::kFormat, "face corner 3 '/3' is not v"},
        BadFace{"1 2 3/1/1/1", ErrorCode::kFormat,
                "face corner 3 '3/1/1/1' has more than two '/'"}));

TEST(ObjStrict, LongPolygonWithARepeatedCornerFails) {
  std::string text;
  std::string face = "f";
  for (int i = 1; i <= 40; ++i) {
    text += "v " + std::to_string(i) + " " + std::to_string(i * i) + " 0\n";
    face += " " + std::to_string(i);
  }
  const std::string path = file_with("long.obj", text + face + " 17\n");
  EXPECT_TRUE(LoadFails(path, ErrorCode::kInvalidMesh, "line 41",
                        {"face uses vertex 17 at corners 17 and 41"}));
}

TEST(ObjStrict, StatementsOutsideTheFormatFail) {
  EXPECT_TRUE(LoadFails(file_with("unknown.obj", kFourVertices + "vc 1 0 0\nf 1 2 3\n"),
                        ErrorCode::kFormat, "line 5", {"line 5: unknown statement 'vc'"}));
  EXPECT_TRUE(LoadFails(file_with("surface.obj", kFourVertices + "surf 0 1 0 1 1 2 3 4\n"),
                        ErrorCode::kFormat, "line 5", {"free-form geometry ('surf')"}));
  EXPECT_TRUE(LoadFails(file_with("continued.obj", kFourVertices + "f 1 2 \\\n3\n"),
                        ErrorCode::kFormat, "line 5", {"line continuation"}));
  EXPECT_TRUE(LoadFails(file_with("short.obj", "v 1 2\n"), ErrorCode::kFormat, "line 1",
                        {"'v' needs x y z"}));
  EXPECT_TRUE(LoadFails(file_with("normal.obj", kFourVertices + "vn 0 0\n"), ErrorCode::kFormat,
                        "line 5", {"'vn' needs x y z; found 2 numbers"}));
  EXPECT_TRUE(LoadFails(file_with("nothing.obj", "# only a comment\n"), ErrorCode::kFormat,
                        "positions", {"no 'v' lines"}));
}

TEST(ObjStrict, AllowedStatementsCommentsAndLineEnds) {
  const std::string path =
      file_with("allowed.obj",
                "\xEF\xBB\xBF# exported\r\nmtllib fish.mtl\r\no fish\r\n"
                "v 0 0 0 # inline comment\r\n\tv 1 0 0 1.0\r\nv 0 1 0 0.5 0.5 0.5\r\nv 1 1 0 1 0.2 "
                "0.3 0.4\r\n"
                "vp 0.5\r\nvt 0.25\r\nvt 0.5 0.75 0\r\nvn 0 0 1\r\nusemtl skin\r\ns off\r\ns 1\r\n"
                "l 1 2\r\np 3\r\n\r\n   \r\nf 1/1 2/2 3/1\r\nf 2//1 4//1 3//1\r\n");
  const Mesh mesh = load_mesh(path);
  ASSERT_EQ(mesh.vertex_count(), 4u);
  EXPECT_EQ(mesh.positions[3], glm::vec3(1, 1, 0));
  EXPECT_EQ(mesh.indices, (std::vector<std::uint32_t>{0, 1, 2, 1, 3, 2}));
  ASSERT_EQ(mesh.texcoords.size(), 4u);
  EXPECT_EQ(mesh.texcoords[0], glm::vec2(0.25f, 0.0f));  // v defaults to 0
  EXPECT_EQ(mesh.texcoords[1], glm::vec2(0.5f, 0.75f));
  EXPECT_EQ(mesh.texcoords[3], glm::vec2(0.0f, 0.0f));  // never given one
  EXPECT_EQ(mesh.normals[3], glm::vec3(0, 0, 1));
  ASSERT_EQ(mesh.groups.size(), 1u);
  EXPECT_EQ(mesh.groups[0].name, "fish");
}

TEST(ObjStrict, ManyGroupsAreReadInLinearTime) {
  // 200,000 distinct group names: looking each up among all before it took minutes.
  std::string text = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
  for (int i = 0; i < 200000; ++i) text += "g group" + std::to_string(i) + "\nf 1 2 3\n";
  const std::string path = file_with("groups.obj", text);
  EXPECT_TRUE(FinishesWithin(
      10,
      [&] {
        const Mesh mesh = load_mesh(path);
        ASSERT_EQ(mesh.groups.size(), 200000u);
        EXPECT_EQ(mesh.groups.back().name, "group199999");
        EXPECT_EQ(mesh.groups.back().first_triangle, 199999u);
      },
      [] {}));
}

TEST(ObjStrict, NegativeAndForwardIndices) {
  // Faces may come before the vertices they name (positive indices); negative ones
  // count back from the statements before the face.
  const std::string path = file_with("forward.obj",
                                     "f 1/1/1 2/1/1 3/1/1\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0.5 0.5\n"
                                     "vn 0 0 1\nv 1 1 0\nf -3/-1/-1 -1/-1/-1 -2/-1/-1\n");
  const Mesh mesh = load_mesh(path);
  EXPECT_EQ(mesh.indices, (std::vector<std::uint32_t>{0, 1, 2, 1, 3, 2}));
  EXPECT_EQ(mesh.texcoords[3], glm::vec2(0.5f, 0.5f));
  EXPECT_TRUE(LoadFails(file_with("back.obj", "v 0 0 0\nf -1 -2 -1\n"), ErrorCode::kInvalidMesh,
                        "line 2",
                        {"face corner 2: v index -2 is out of range (1 'v' lines before it)"}));
}

// ---------------------------------------------------------------------------------
// STL

std::string ascii_stl(const std::string& second_vertex) {
  return "solid fish\n facet normal 0 0 1\n  outer loop\n   vertex 0 0 0\n   vertex " +
         second_vertex + "\n   vertex 0 1 0\n  endloop\n endfacet\nendsolid fish\n";
}

// OpenMesh read unreadable ASCII numbers as 0.
TEST(StlStrict, AsciiNumbersMustBeReadable) {
  EXPECT_TRUE(LoadFails(file_with("abc.stl", ascii_stl("1 abc 0")), ErrorCode::kFormat, "line 5",
                        {"line 5: vertex y 'abc' is not a number"}));
  EXPECT_TRUE(LoadFails(file_with("nan.stl", ascii_stl("1 0 nan")), ErrorCode::kInvalidMesh,
                        "line 5", {"vertex z 'nan' is not finite"}));
  EXPECT_TRUE(LoadFails(file_with("few.stl", ascii_stl("1 0")), ErrorCode::kFormat, "line 5",
                        {"'vertex' needs 3 numbers, found 2"}));
  EXPECT_TRUE(LoadFails(file_with("normal.stl", "solid\nfacet normal 0 x 1\n"), ErrorCode::kFormat,
                        "line 2", {"facet normal y 'x' is not a number"}));
}

TEST(StlStrict, AsciiStructureIsChecked) {
  EXPECT_TRUE(LoadFails(file_with("open.stl",
                                  "solid a\n facet normal 0 0 1\n  outer loop\n"
                                  "   vertex 0 0 0\n   vertex 1 0 0\n   vertex 0 1 0\n"
                                  "  endloop\n endfacet\n"),
                        ErrorCode::kFormat, "line 8",
                        {"the file ends inside the solid of line 1"}));
  EXPECT_TRUE(LoadFails(file_with("four.stl",
                                  "solid a\n facet normal 0 0 1\n  outer loop\n"
                                  "   vertex 0 0 0\n   vertex 1 0 0\n   vertex 0 1 0\n"
                                  "   vertex 1 1 0\n  endloop\n endfacet\nendsolid\n"),
                        ErrorCode::kFormat, "line 7", {"expected 'endloop'"}));
  EXPECT_TRUE(LoadFails(file_with("after.stl", ascii_stl("1 0 0") + "garbage\n"),
                        ErrorCode::kFormat, "line 10",
                        {"expected 'solid' or the end of the file"}));
  EXPECT_TRUE(LoadFails(file_with("empty_solid.stl", "solid a\nendsolid a\n"), ErrorCode::kFormat,
                        "positions", {"no facets"}));
}

TEST(StlStrict, AsciiKeepsEveryFacetAndMergesEqualPositions) {
  // Two solids, upper-case keywords, a degenerate facet, -0 and +0, NaN facet normals.
  const std::string path = file_with(
      "two.stl",
      "solid a\nFACET NORMAL nan nan nan\nOUTER LOOP\nVERTEX 0 0 0\nVERTEX 1 0 0\nVERTEX 0 1 0\n"
      "ENDLOOP\nENDFACET\nENDSOLID a\nsolid b\nfacet normal 0 0 0\nouter loop\nvertex 1 0 0\n"
      "vertex -0 0 0\nvertex 1 0 0\nendloop\nendfacet\nendsolid\n");
  const Mesh mesh = load_mesh(path);
  EXPECT_EQ(mesh.vertex_count(), 3u);
  EXPECT_EQ(mesh.indices, (std::vector<std::uint32_t>{0, 1, 2, 1, 0, 1}));
}

std::string binary_stl(std::uint32_t declared, const std::vector<float>& corners) {
  std::string bytes(80, ' ');
  append(bytes, declared);
  for (std::size_t t = 0; t < corners.size() / 9; ++t) {
    for (int k = 0; k < 3; ++k) append(bytes, 0.0f);
    for (std::size_t k = 0; k < 9; ++k) append(bytes, corners[9 * t + k]);
    append(bytes, std::uint16_t{0});
  }
  return bytes;
}

TEST(StlStrict, BinarySizeMustMatchTheCountAndCornersBeFinite) {
  const std::vector<float> triangle = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  EXPECT_TRUE(LoadFails(file_with("count.stl", binary_stl(5, triangle)), ErrorCode::kFormat, "path",
                        {"declares 5 triangles, which take 84 + 50 * 5 = 334 bytes, but the file "
                         "has 134"}));
  EXPECT_TRUE(LoadFails(file_with("huge.stl", binary_stl(4000000000u, triangle)),
                        ErrorCode::kFormat, "path", {"declares 4000000000 triangles"}));
  std::vector<float> nan_corner = triangle;
  nan_corner[4] = std::numeric_limits<float>::quiet_NaN();
  EXPECT_TRUE(LoadFails(file_with("nan.stl", binary_stl(1, nan_corner)), ErrorCode::kInvalidMesh,
                        "triangles[0]", {"triangles[0]: corner 2 y is NaN"}));
  std::string solid_header = binary_stl(3, triangle);
  solid_header.replace(0, 5, "solid");  // a binary header that starts like ASCII
  EXPECT_TRUE(LoadFails(file_with("solid.stl", solid_header), ErrorCode::kFormat, "line",
                        {"as binary STL its header declares 3 triangles"}));
  EXPECT_TRUE(LoadFails(file_with("tiny.stl", "abc"), ErrorCode::kFormat, "path",
                        {"less than the 84-byte header"}));
}

// ---------------------------------------------------------------------------------
// OFF

TEST(OffStrict, DeclaredCountsAreCheckedBeforeAllocating) {
  const std::string huge =
      file_with("huge.off", "OFF\n2000000000 2000000000 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  EXPECT_TRUE(LoadFails(huge, ErrorCode::kFormat, "line 2",
                        {"the header declares 2000000000 vertices and 2000000000 faces, but the 26 "
                         "bytes after it cannot hold them"}));
  EXPECT_LT(largest_allocation([&] { load_mesh(huge); }), std::size_t{1} << 20);
  EXPECT_TRUE(LoadFails(file_with("negative.off", "OFF\n-3 1 0\n0 0 0\n"), ErrorCode::kFormat,
                        "line 2", {"vertex count -3 is negative"}));
  EXPECT_TRUE(LoadFails(file_with("negative_faces.off", "OFF 3 -1 0\n0 0 0\n1 0 0\n0 1 0\n"),
                        ErrorCode::kFormat, "line 1", {"face count -1 is negative"}));
  EXPECT_TRUE(LoadFails(file_with("overflow.off", "OFF\n99999999999999999999 1 0\n"),
                        ErrorCode::kInvalidMesh, "line 2", {"vertex count", "is out of range"}));
}

TEST(OffStrict, BadNumbersAndFacesFailNamingTheLine) {
  // Files long enough for their counts (see DeclaredCountsAreCheckedBeforeAllocating).
  const std::string head = "OFF\n3 1 0\n0 0 0\n";
  const std::string padding = "# padding\n";
  EXPECT_TRUE(LoadFails(file_with("nan.off", head + "1 nan 0\n0 1 0\n3 0 1 2\n"),
                        ErrorCode::kInvalidMesh, "line 4",
                        {"line 4: vertex y 'nan' is not finite"}));
  EXPECT_TRUE(LoadFails(file_with("abc.off", head + "1 0 abc\n0 1 0\n3 0 1 2\n"),
                        ErrorCode::kFormat, "line 4", {"vertex z 'abc' is not a number"}));
  EXPECT_TRUE(LoadFails(file_with("few.off", head + "1 0\n0 1 0\n3 0 1 2\n" + padding),
                        ErrorCode::kFormat, "line 4",
                        {"vertex line has 2 numbers, the header keyword asks for 3"}));
  EXPECT_TRUE(LoadFails(file_with("index.off", head + "1 0 0\n0 1 0\n3 0 1 x\n"),
                        ErrorCode::kFormat, "line 6", {"face 0 corner 3 'x' is not an integer"}));
  EXPECT_TRUE(LoadFails(file_with("repeat.off", head + "1 0 0\n0 1 0\n3 0 1 0\n"),
                        ErrorCode::kInvalidMesh, "line 6",
                        {"face 0 uses vertex 0 at corners 1 and 3"}));
  EXPECT_TRUE(LoadFails(file_with("two.off", head + "1 0 0\n0 1 0\n2 0 1\n" + padding),
                        ErrorCode::kFormat, "line 6",
                        {"face 0 has corner count 2, at least 3 needed"}));
  EXPECT_TRUE(LoadFails(file_with("missing.off", head + "1 0 0\n0 1 0\n4 0 1 2\n"),
                        ErrorCode::kFormat, "line 6",
                        {"corner count 4, but only 3 numbers follow"}));
  EXPECT_TRUE(LoadFails(file_with("after.off", head + "1 0 0\n0 1 0\n3 0 1 2\n3 0 2 1\n"),
                        ErrorCode::kFormat, "line 7", {"content after the last of the 1 faces"}));
  EXPECT_TRUE(
      LoadFails(file_with("ends.off", "OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n" + padding),
                ErrorCode::kFormat, "line 7", {"the file ends after 1 of the 2 faces"}));
  EXPECT_TRUE(LoadFails(file_with("binary.off", "OFF BINARY\n"), ErrorCode::kFormat, "line 1",
                        {"binary OFF is not supported"}));
  EXPECT_TRUE(
      LoadFails(file_with("4d.off", "4OFF\n"), ErrorCode::kFormat, "line 1", {"only 3D vertices"}));
}

TEST(OffStrict, HeaderVariantsCommentsAndColors) {
  const Mesh normals =
      load_mesh(file_with("normals.off",
                          "# comment\nNOFF 3 1 0\n0 0 0 0 0 2\n1 0 0 0 0 1 # a comment\n"
                          "0 1 0 0 0 1\n\n3 0 1 2 255 0 0\n"));
  EXPECT_EQ(normals.normals[0], glm::vec3(0, 0, 1));
  const Mesh textured = load_mesh(
      file_with("textured.off",
                "STCOFF\n3 1\n0 0 0 1 1 1 0.25 0.5\n1 0 0 1 1 1 1 1 0\n0 1 0 0 0 0 0 1 1\n"
                "3 0 1 2\n"));
  ASSERT_EQ(textured.texcoords.size(), 3u);
  EXPECT_EQ(textured.texcoords[0], glm::vec2(0.25f, 0.5f));
  EXPECT_EQ(textured.texcoords[2], glm::vec2(1.0f, 1.0f));
  const Mesh dimension =
      load_mesh(file_with("n.off", "nOFF 3\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"));
  EXPECT_EQ(dimension.triangle_count(), 1u);
}

// ---------------------------------------------------------------------------------
// PLY

std::string ply_header(const std::string& format, const std::string& elements) {
  return "ply\nformat " + format + " 1.0\ncomment test\n" + elements + "end_header\n";
}

const std::string kAsciiVertexFace =
    "element vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
    "element face 1\nproperty list uchar int vertex_indices\n";

TEST(PlyStrict, DeclaredCountsAreCheckedBeforeAllocating) {
  const std::string huge = file_with(
      "huge.ply", ply_header("ascii",
                             "element vertex 4000000000\nproperty float x\nproperty float "
                             "y\nproperty float z\n") +
                      "0 0 0\n");
  EXPECT_TRUE(LoadFails(huge, ErrorCode::kFormat, "line 4",
                        {"element 'vertex' declares 4000000000 entries of at least 3 bytes, but "
                         "only 6 bytes of data are left"}));
  EXPECT_LT(largest_allocation([&] { load_mesh(huge); }), std::size_t{1} << 20);

  std::string binary = ply_header("binary_little_endian",
                                  "element vertex 3\nproperty float x\nproperty float y\nproperty "
                                  "float z\nelement face 1000000000\nproperty list uchar int "
                                  "vertex_indices\n");
  for (int i = 0; i < 9; ++i) append(binary, 0.5f * static_cast<float>(i % 2));
  const std::string faces = file_with("faces.ply", binary);
  EXPECT_TRUE(LoadFails(faces, ErrorCode::kFormat, "line 8",
                        {"element 'face' declares 1000000000 entries of at least 1 bytes, but only "
                         "0 bytes"}));
  EXPECT_LT(largest_allocation([&] { load_mesh(faces); }), std::size_t{1} << 20);

  const std::string empty_element = file_with(
      "empty.ply", ply_header("ascii", "element nothing 99999999999\n" + kAsciiVertexFace) +
                       "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  EXPECT_TRUE(LoadFails(empty_element, ErrorCode::kFormat, "line 4",
                        {"element 'nothing' has 99999999999 entries but no properties"}));
  EXPECT_TRUE(LoadFails(file_with("negative.ply", ply_header("ascii", "element vertex -1\n")),
                        ErrorCode::kFormat, "line 4", {"element count -1 is negative"}));
}

TEST(PlyStrict, ListCountsAreCheckedAgainstTheBytesLeft) {
  std::string binary = ply_header("binary_little_endian",
                                  "element vertex 3\nproperty float x\nproperty float y\n"
                                  "property float z\nelement face 1\nproperty list uint "
                                  "int vertex_indices\n");
  for (int i = 0; i < 9; ++i) append(binary, 1.0f * static_cast<float>(i % 3));
  append(binary, std::uint32_t{3000000000u});
  append(binary, std::int32_t{0});
  const std::string path = file_with("list.ply", binary);
  EXPECT_TRUE(LoadFails(path, ErrorCode::kFormat, "face[0].vertex_indices",
                        {"list count 3000000000 exceeds the 4 bytes left"}));
  EXPECT_LT(largest_allocation([&] { load_mesh(path); }), std::size_t{1} << 20);
}

TEST(PlyStrict, ValuesMustBeReadableAndFitTheirType) {
  const std::string head = ply_header("ascii", kAsciiVertexFace);
  EXPECT_TRUE(LoadFails(file_with("nan.ply", head + "0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n"),
                        ErrorCode::kInvalidMesh, "vertex[1].y", {"vertex[1].y (line 12): is NaN"}));
  EXPECT_TRUE(LoadFails(file_with("abc.ply", head + "0 0 0\n1 0 abc\n0 1 0\n3 0 1 2\n"),
                        ErrorCode::kFormat, "vertex[1].z",
                        {"vertex[1].z (line 12): 'abc' is not a number"}));
  EXPECT_TRUE(LoadFails(file_with("big.ply", head + "0 0 0\n1e39 0 0\n0 1 0\n3 0 1 2\n"),
                        ErrorCode::kInvalidMesh, "vertex[1].x", {"is outside the range of float"}));
  EXPECT_TRUE(LoadFails(file_with("count.ply", head + "0 0 0\n1 0 0\n0 1 0\n300 0 1 2\n"),
                        ErrorCode::kFormat, "face[0].vertex_indices",
                        {"'300' is outside the range of uchar"}));
  EXPECT_TRUE(LoadFails(file_with("short.ply", head + "0 0 0\n1 0 0\n0 1 0\n3 0 1\n"),
                        ErrorCode::kFormat, "face[0].vertex_indices[2]",
                        {"the data ends before this value"}));
  EXPECT_TRUE(LoadFails(file_with("after.ply", head + "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n7\n"),
                        ErrorCode::kFormat, "path", {"bytes follow the last element"}));
}

TEST(PlyStrict, FacesNeedThreeDistinctExistingVertices) {
  const std::string head = ply_header("ascii", kAsciiVertexFace);
  const std::string vertices = "0 0 0\n1 0 0\n0 1 0\n";
  EXPECT_TRUE(LoadFails(file_with("range.ply", head + vertices + "3 0 1 3\n"),
                        ErrorCode::kInvalidMesh, "face[0].vertex_indices[2]",
                        {"(line 14): vertex index 3 is out of range (3 vertices)"}));
  EXPECT_TRUE(LoadFails(file_with("negative.ply", head + vertices + "3 0 -1 2\n"),
                        ErrorCode::kInvalidMesh, "face[0].vertex_indices[1]",
                        {"vertex index -1 is out of range"}));
  EXPECT_TRUE(LoadFails(file_with("repeat.ply", head + vertices + "3 0 1 1\n"),
                        ErrorCode::kInvalidMesh, "face[0]", {"uses vertex 1 at corners 2 and 3"}));
  EXPECT_TRUE(LoadFails(file_with("two.ply", head + vertices + "2 0 1\n"), ErrorCode::kFormat,
                        "face[0].vertex_indices", {"face has 2 corners, at least 3 needed"}));
}

TEST(PlyStrict, HeaderErrorsNameTheLine) {
  EXPECT_TRUE(LoadFails(file_with("type.ply", ply_header("ascii",
                                                         "element vertex 1\nproperty "
                                                         "real x\n")),
                        ErrorCode::kFormat, "line 5", {"unknown type 'real'"}));
  EXPECT_TRUE(LoadFails(file_with("format.ply", ply_header("binary_middle_endian", "")),
                        ErrorCode::kFormat, "line 2", {"unknown format 'binary_middle_endian'"}));
  EXPECT_TRUE(LoadFails(file_with("no_end.ply", "ply\nformat ascii 1.0\nelement vertex 1\n"),
                        ErrorCode::kFormat, "line", {"no 'end_header'"}));
  EXPECT_TRUE(LoadFails(
      file_with("strips.ply", ply_header("ascii", kAsciiVertexFace + "element tristrips 1\n"
                                                                     "property list int int "
                                                                     "vertex_indices\n")),
      ErrorCode::kFormat, "line 10", {"element 'tristrips' (triangle strips)"}));
  EXPECT_TRUE(LoadFails(file_with("no_z.ply", ply_header("ascii",
                                                         "element vertex 1\nproperty "
                                                         "float x\nproperty float y\n") +
                                                  "0 0\n"),
                        ErrorCode::kFormat, "line 4", {"element 'vertex' has no property 'z'"}));
}

// Found by fuzz_ply: an element name with a NUL byte went into the field and the
// message as it was, and what() ended at the NUL.
TEST(PlyStrict, NamesFromTheFileAreMadePrintableInErrors) {
  std::string elements = "element vertex 3\nproperty float x\nproperty float y\nproperty float z\n";
  elements += std::string("element fa\0c 1\n", 15);
  elements += "property list ushort uint vertex_index\n";
  const std::string path =
      file_with("names.ply", ply_header("ascii", elements) + "0 0 0\n1 0 0\n0 1 0\n3 2 1 x\n");
  EXPECT_TRUE(LoadFails(path, ErrorCode::kFormat, "fa?c[0].vertex_index[2]",
                        {"fa?c[0].vertex_index[2] (line 14): 'x' is not an integer"}));
}

TEST(PlyStrict, NamesAreUniqueAndCheckedInLinearTime) {
  EXPECT_TRUE(LoadFails(file_with("elements.ply", ply_header("ascii",
                                                             "element vertex 0\nelement "
                                                             "vertex 0\n")),
                        ErrorCode::kFormat, "line 5", {"a second element 'vertex'"}));
  EXPECT_TRUE(LoadFails(
      file_with("properties.ply",
                ply_header("ascii", kAsciiVertexFace + "property int vertex_indices\n")),
      ErrorCode::kFormat, "line 10", {"element 'face' has a second property 'vertex_indices'"}));
  // 200,000 elements: comparing each with all before it took minutes.
  std::string elements;
  for (int i = 0; i < 200000; ++i) elements += "element e" + std::to_string(i) + " 0\n";
  const std::string path = file_with("many.ply", ply_header("ascii", elements));
  EXPECT_TRUE(FinishesWithin(
      10,
      [&] {
        EXPECT_TRUE(LoadFails(path, ErrorCode::kFormat, "positions", {"declares no vertices"}));
      },
      [] {}));
}

TEST(PlyStrict, BigEndianDoublesFacesFirstAndDroppedProperties) {
  // The face element comes first; vertices are doubles with a color, big endian.
  std::string ply =
      ply_header("binary_big_endian",
                 "element face 1\nproperty uchar flags\nproperty list uchar uint vertex_indices\n"
                 "element vertex 3\nproperty double x\nproperty double y\nproperty double z\n"
                 "property uchar red\nproperty float u\nproperty float v\n");
  ply += '\x07';
  ply += '\x03';
  for (const std::uint32_t index : {2u, 1u, 0u}) append_big_endian(ply, index);
  const double xyz[3][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  for (const auto& vertex : xyz) {
    for (const double c : vertex) append_big_endian(ply, c);
    ply += '\xff';
    append_big_endian(ply, 0.25f);
    append_big_endian(ply, 0.75f);
  }
  const Mesh mesh = load_mesh(file_with("big_endian.ply", ply));
  ASSERT_EQ(mesh.vertex_count(), 3u);
  EXPECT_EQ(mesh.positions[1], glm::vec3(1, 0, 0));
  EXPECT_EQ(mesh.indices, (std::vector<std::uint32_t>{2, 1, 0}));
  EXPECT_EQ(mesh.texcoords[2], glm::vec2(0.25f, 0.75f));
}

// ---------------------------------------------------------------------------------
// Only regular files are read

TEST(SpecialFiles, FifoIsRefusedAtOnce) {
  const std::string path = temp_path("pipe.obj");
  ASSERT_EQ(::mkfifo(path.c_str(), 0600), 0);
  ::testing::AssertionResult refused = ::testing::AssertionFailure();
  EXPECT_TRUE(FinishesWithin(
      10,
      [&] {
        refused =
            LoadFails(path, ErrorCode::kIo, "path", {"is a FIFO (named pipe), not a regular file"});
      },
      [&] { release_fifo_reader(path); }));
  EXPECT_TRUE(refused);
}

TEST(SpecialFiles, DeviceIsRefused) {
  EXPECT_TRUE(LoadFails("/dev/zero", ErrorCode::kIo, "path",
                        {"is a character device, not a regular file"}));
  const std::string link = temp_path("zero.obj");
  fs::create_symlink("/dev/zero", link);
  EXPECT_TRUE(FinishesWithin(
      10, [&] { EXPECT_TRUE(LoadFails(link, ErrorCode::kIo, "path", {"is a character device"})); },
      [] {}));
  const std::string folder = temp_path("folder.stl");
  fs::create_directory(folder);
  EXPECT_TRUE(LoadFails(folder, ErrorCode::kIo, "path", {"is a directory"}));
}

// ---------------------------------------------------------------------------------
// glTF

// A .gltf file `name` with an external buffer "mesh.bin" holding `vertex_count`
// float positions (x = index), a POSITION accessor 0 over them, mesh 0 with one
// primitive, and `members` (more top-level JSON members, each with a leading comma).
std::string gltf_with_nodes(const std::string& name, const std::string& members,
                            std::size_t vertex_count = 3) {
  const std::string path = temp_path(name);
  std::string bin;
  for (std::size_t v = 0; v < vertex_count; ++v) {
    append(bin, static_cast<float>(v));
    append(bin, static_cast<float>(v % 2));
    append(bin, static_cast<float>(v % 3));
  }
  write_file((fs::path(path).parent_path() / "mesh.bin").string(), bin);
  const std::string size = std::to_string(bin.size());
  write_file(path,
             "{\"asset\":{\"version\":\"2.0\"},\"buffers\":[{\"uri\":\"mesh.bin\","
             "\"byteLength\":" +
                 size + "}],\"bufferViews\":[{\"buffer\":0,\"byteLength\":" + size +
                 "}],\"accessors\":[{\"bufferView\":0,\"componentType\":5126,"
                 "\"count\":" +
                 std::to_string(vertex_count) +
                 ",\"type\":\"VEC3\"}],\"meshes\":[{\"primitives\":[{\"attributes\":"
                 "{\"POSITION\":0}}]}]" +
                 members + "}");
  return path;
}

TEST(GltfStrict, ANodeHasOnePlaceInTheScene) {
  // Loaded twice (two copies of the triangle) before.
  EXPECT_TRUE(LoadFails(
      gltf_with_nodes("twice.gltf", ",\"nodes\":[{\"children\":[1,1]},{\"mesh\":0}]"),
      ErrorCode::kFormat, "nodes[1]", {"nodes[1]: is listed twice in nodes[0].children"}));
  EXPECT_TRUE(LoadFails(gltf_with_nodes("shared.gltf",
                                        ",\"nodes\":[{\"children\":[2]},{\"children\":[2]},"
                                        "{\"mesh\":0}],\"scenes\":[{\"nodes\":[0,1]}]"),
                        ErrorCode::kFormat, "nodes[2]",
                        {"nodes[2]: is a child of both nodes[0] and nodes[1]"}));
  EXPECT_TRUE(LoadFails(gltf_with_nodes("root.gltf",
                                        ",\"nodes\":[{\"children\":[1]},{\"mesh\":0}],"
                                        "\"scenes\":[{\"nodes\":[0,1]}]"),
                        ErrorCode::kFormat, "nodes[1]",
                        {"is listed in scenes[0].nodes but is a child of nodes[0]"}));
  EXPECT_TRUE(LoadFails(gltf_with_nodes("scene_twice.gltf",
                                        ",\"nodes\":[{\"mesh\":0}],\"scenes\":[{\"nodes\":[0,0]}]"),
                        ErrorCode::kFormat, "nodes[0]", {"is listed twice in scenes[0].nodes"}));
  EXPECT_TRUE(LoadFails(gltf_with_nodes("missing.gltf", ",\"nodes\":[{\"children\":[5]}]"),
                        ErrorCode::kFormat, "nodes[0].children[0]",
                        {"node 5 does not exist (1 nodes)"}));
}

TEST(GltfStrict, SharedChildrenEndAtOnceInsteadOfAnExponentialWalk) {
  // Node i lists node i + 1 twice: 2^40 paths down to the last node.
  std::string nodes = ",\"nodes\":[";
  for (int i = 0; i < 40; ++i)
    nodes += "{\"children\":[" + std::to_string(i + 1) + "," + std::to_string(i + 1) + "]},";
  nodes += "{\"mesh\":0}],\"scenes\":[{\"nodes\":[0]}]";
  const std::string path = gltf_with_nodes("dag.gltf", nodes);
  EXPECT_TRUE(FinishesWithin(
      60,
      [&] { EXPECT_TRUE(LoadFails(path, ErrorCode::kFormat, "nodes[1]", {"is listed twice"})); },
      [] {}));
}

TEST(GltfStrict, CyclesAreErrorsEvenOutsideTheScene) {
  EXPECT_TRUE(LoadFails(gltf_with_nodes("cycle.gltf",
                                        ",\"nodes\":[{\"children\":[1]},{\"children\":[0],"
                                        "\"mesh\":0}],\"scenes\":[{\"nodes\":[0]}]"),
                        ErrorCode::kFormat, "nodes[", {"is its own ancestor (cycle in children)"}));
  // Without scenes the roots are the nodes without parents: a cycle has none, and its
  // meshes were dropped silently before.
  EXPECT_TRUE(LoadFails(gltf_with_nodes("hidden_cycle.gltf",
                                        ",\"nodes\":[{\"mesh\":0},{\"children\":[2],\"mesh\":0},"
                                        "{\"children\":[1]}]"),
                        ErrorCode::kFormat, "nodes[1]", {"is its own ancestor"}));
  EXPECT_TRUE(LoadFails(gltf_with_nodes("self.gltf", ",\"nodes\":[{\"children\":[0],\"mesh\":0}]"),
                        ErrorCode::kFormat, "nodes[0]", {"is its own ancestor"}));
}

// A chain of `length` nodes, each the only child of the one before; the last holds
// the mesh.
std::string node_chain(std::size_t length) {
  std::string nodes = ",\"nodes\":[";
  for (std::size_t i = 0; i + 1 < length; ++i) {
    nodes += "{\"children\":[" + std::to_string(i + 1) + "]},";
  }
  return nodes + "{\"mesh\":0,\"translation\":[1,0,0]}],\"scenes\":[{\"nodes\":[0]}]";
}

TEST(GltfStrict, NodeDepthIsLimitedAndWalkedWithoutRecursion) {
  const Mesh deep = load_mesh(gltf_with_nodes("1024.gltf", node_chain(1024)));
  EXPECT_EQ(deep.positions[0], glm::vec3(1, 0, 0));
  EXPECT_TRUE(LoadFails(gltf_with_nodes("1025.gltf", node_chain(1025)), ErrorCode::kFormat,
                        "nodes[1024]",
                        {"nodes[1024]: is nested 1025 levels deep, more than the limit of 1024"}));
  // Deep enough to overflow the stack of a recursive walk.
  EXPECT_TRUE(LoadFails(gltf_with_nodes("200000.gltf", node_chain(200000)), ErrorCode::kFormat,
                        "nodes[1024]", {"more than the limit of 1024"}));
}

TEST(GltfStrict, DeeplyNestedJsonIsRefusedBeforeParsing) {
  const std::string deep(100000, '[');
  const std::string path =
      gltf_with_nodes("extras.gltf", ",\"nodes\":[{\"mesh\":0,\"extras\":" + deep +
                                         std::string(100000, ']') + "}]");
  EXPECT_TRUE(LoadFails(path, ErrorCode::kFormat, "path",
                        {"JSON arrays and objects nest deeper than 64 levels (line 1, byte"}));
  // 64 levels in all are fine, and brackets inside strings do not count.
  const std::string nested = std::string(59, '[') + std::string(59, ']');
  const Mesh mesh = load_mesh(gltf_with_nodes(
      "fine.gltf",
      ",\"nodes\":[{\"mesh\":0,\"name\":\"[[[[[[[[[[[[\\\"\",\"extras\":{\"a\":" + nested + "}}]"));
  EXPECT_EQ(mesh.vertex_count(), 3u);
}

// A GLB file around `json` and `bin` (padded as the format requires).
std::string glb(std::string json, std::string bin, std::uint32_t bin_length_delta = 0) {
  while (json.size() % 4 != 0) json += ' ';
  while (bin.size() % 4 != 0) bin += '\0';
  std::string out = "glTF";
  append(out, std::uint32_t{2});
  const std::size_t total = 12 + 8 + json.size() + (bin.empty() ? 0 : 8 + bin.size());
  append(out, static_cast<std::uint32_t>(total));
  append(out, static_cast<std::uint32_t>(json.size()));
  out += "JSON";
  out += json;
  if (!bin.empty()) {
    append(out, static_cast<std::uint32_t>(bin.size() + bin_length_delta));
    out += std::string("BIN\0", 4);
    out += bin;
  }
  return out;
}

const std::string kGlbTriangleJson =
    "{\"asset\":{\"version\":\"2.0\"},\"buffers\":[{\"byteLength\":36}],\"bufferViews\":["
    "{\"buffer\":0,\"byteLength\":36}],\"accessors\":[{\"bufferView\":0,\"componentType\":5126,"
    "\"count\":3,\"type\":\"VEC3\"}],\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0}"
    "}]}],\"nodes\":[{\"mesh\":0}]}";

std::string triangle_bin() {
  std::string bin;
  for (const float c : {0.0f, 0.0f, 0.0f, 1.0f, 0.0f, 0.0f, 0.0f, 1.0f, 0.0f}) append(bin, c);
  return bin;
}

TEST(GltfStrict, GlbChunkLengthsAreCheckedAgainstTheFile) {
  EXPECT_EQ(load_mesh(file_with("ok.glb", glb(kGlbTriangleJson, triangle_bin()))).vertex_count(),
            3u);
  // A BIN chunk 8 bytes longer than the file: tinygltf read past the end of the data.
  EXPECT_TRUE(LoadFails(file_with("bin.glb", glb(kGlbTriangleJson, triangle_bin(), 8)),
                        ErrorCode::kFormat, "path",
                        {"GLB: the BIN chunk's length 44 exceeds the 36 bytes after its header"}));
  std::string long_json = glb(kGlbTriangleJson, triangle_bin());
  long_json[12] = '\x7f';
  long_json[13] = '\x7f';
  EXPECT_TRUE(LoadFails(file_with("json.glb", long_json), ErrorCode::kFormat, "path",
                        {"GLB: the JSON chunk's length 32639 exceeds"}));
  std::string length = glb(kGlbTriangleJson, triangle_bin());
  length += "trailing";
  EXPECT_TRUE(LoadFails(file_with("length.glb", length), ErrorCode::kFormat, "path",
                        {"GLB: the header gives the length"}));
  const std::string deep =
      glb("{\"a\":" + std::string(1000, '[') + std::string(1000, ']') + "}", "");
  EXPECT_TRUE(LoadFails(file_with("deep.glb", deep), ErrorCode::kFormat, "path",
                        {"nest deeper than 64 levels"}));
}

TEST(GltfStrict, AccessorsWithoutDataAreBoundedByTheInput) {
  // An accessor without bufferView is all zeros: its count is not backed by any byte.
  const std::string path = gltf_with_nodes(
      "zeros.gltf",
      ",\"nodes\":[{\"mesh\":1}],\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0}}]},"
      "{\"primitives\":[{\"attributes\":{\"POSITION\":1}}]}],\"accessors\":[{\"bufferView\":0,"
      "\"componentType\":5126,\"count\":3,\"type\":\"VEC3\"},{\"componentType\":5126,\"count\":"
      "4000000000,\"type\":\"VEC3\"}]");
  EXPECT_TRUE(LoadFails(path, ErrorCode::kFormat, "meshes[1].primitives[0].POSITION",
                        {"accessor 1 has no bufferView (all zeros) and count 4000000000, more than "
                         "the"}));
  EXPECT_LT(largest_allocation([&] { load_mesh(path); }), std::size_t{1} << 20);
}

TEST(GltfStrict, InstancingIsBoundedByTheInputSize) {
  // 3000 nodes place a 3000-vertex mesh each: 9 million vertices from a 70 kB input.
  std::string nodes = ",\"nodes\":[";
  for (int i = 0; i < 3000; ++i) nodes += std::string(i == 0 ? "" : ",") + "{\"mesh\":0}";
  const std::string path = gltf_with_nodes("instances.gltf", nodes + "]", 3000);
  EXPECT_TRUE(LoadFails(path, ErrorCode::kFormat, "nodes[",
                        {"placing meshes[0] here brings the scene to more than",
                         "too many instances of its meshes"}));
  // A few instances are fine.
  EXPECT_EQ(load_mesh(gltf_with_nodes("three.gltf",
                                      ",\"nodes\":[{\"mesh\":0},{\"mesh\":0},"
                                      "{\"mesh\":0}]",
                                      3000))
                .vertex_count(),
            9000u);
}

TEST(GltfStrict, NormalsAreNamedByTheirAccessorElement) {
  // A zero NORMAL was reported under the flattened mesh's index ("normals[1]").
  const std::string base = gltf_with_nodes("zero_normal.gltf", "");
  const fs::path folder = fs::path(base).parent_path();
  std::string bin;
  for (const float c : {0.0f, 0.0f, 0.0f, 1.0f, 0.0f, 0.0f, 0.0f, 1.0f, 0.0f}) append(bin, c);
  for (const float c : {0.0f, 0.0f, 1.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 1.0f}) append(bin, c);
  write_file((folder / "normals.bin").string(), bin);
  const std::string path = (folder / "normals.gltf").string();
  write_file(path,
             "{\"asset\":{\"version\":\"2.0\"},\"buffers\":[{\"uri\":\"normals.bin\","
             "\"byteLength\":72}],\"bufferViews\":[{\"buffer\":0,\"byteLength\":72}],"
             "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":3,\"type\":"
             "\"VEC3\"},{\"bufferView\":0,\"byteOffset\":36,\"componentType\":5126,\"count\":"
             "3,\"type\":\"VEC3\"}],\"meshes\":[{\"primitives\":[{\"attributes\":{"
             "\"POSITION\":0,\"NORMAL\":1}}]}],\"nodes\":[{\"mesh\":0}]}");
  EXPECT_TRUE(LoadFails(path, ErrorCode::kInvalidMesh, "meshes[0].primitives[0].NORMAL[1]",
                        {"meshes[0].primitives[0].NORMAL[1] has zero length"}));
}

TEST(GltfStrict, NodeTransformsMustBeFiniteAndInvertible) {
  EXPECT_TRUE(
      LoadFails(gltf_with_nodes("singular.gltf", ",\"nodes\":[{\"mesh\":0,\"scale\":[1,0,1]}]"),
                ErrorCode::kFormat, "nodes[0]", {"is singular (determinant 0)"}));
  EXPECT_TRUE(LoadFails(
      gltf_with_nodes("rotation.gltf", ",\"nodes\":[{\"mesh\":0,\"rotation\":[0,0,0,0]}]"),
      ErrorCode::kFormat, "nodes[0].rotation", {"a quaternion of zero length"}));
  EXPECT_TRUE(LoadFails(gltf_with_nodes("infinite.gltf",
                                        ",\"nodes\":[{\"children\":[1],\"scale\":[1e200,1,1]},"
                                        "{\"mesh\":0,\"scale\":[1e200,1,1]}]"),
                        ErrorCode::kFormat, "nodes[1]", {"is not finite"}));
  EXPECT_TRUE(
      LoadFails(gltf_with_nodes("huge.gltf", ",\"nodes\":[{\"mesh\":0,\"scale\":[1e300,1,1]}]"),
                ErrorCode::kInvalidMesh, "POSITION",
                {"POSITION[1]: the node's transform takes it outside the float range"}));
}

// Found by fuzz_gltf: the mesh's name was put inside the field's text in the message
// ("meshes[0] ('tri').primitives[0]..."), which then no longer named the field.
TEST(GltfStrict, MessagesNameTheFieldLiterallyAndTheMeshAfterIt) {
  const std::string path =
      gltf_with_nodes("named.gltf",
                      ",\"nodes\":[{\"mesh\":0}],\"meshes\":[{\"name\":\"fin\\u0001\","
                      "\"primitives\":[{\"attributes\":{\"POSITION\":0,\"NORMAL\":5}}]}]");
  EXPECT_TRUE(LoadFails(path, ErrorCode::kFormat, "meshes[0].primitives[0].NORMAL",
                        {"meshes[0].primitives[0].NORMAL: accessor 5 does not exist (1 accessors); "
                         "mesh 'fin?'"}));
}

// tinygltf's messages quote URIs and JSON from the file: an escape sequence reached
// the message (and a terminal) raw, and a data URI made it as long as the file.
TEST(GltfStrict, TinygltfMessagesArePrintableAndShort) {
  const std::string path =
      file_with("escape.gltf",
                "{\"asset\":{\"version\":\"2.0\"},\"buffers\":[{\"byteLength\":3,\"uri\":"
                "\"data:application/octet-stream;base64,\\u001b[2J" +
                    std::string(100000, 'A') + "\"}]}");
  try {
    load_mesh(path);
    FAIL() << "loaded";
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("Failed to decode 'uri' : data:application/octet-stream;base64,?[2JAA"),
              std::string::npos)
        << message;
    EXPECT_LT(message.size(), 1200u);
    for (const char c : message) EXPECT_TRUE(c >= 0x20 && c < 0x7f) << message;
  }
}

TEST(GltfStrict, UrisNamingAFolderOrAFifo) {
  // A buffer URI naming a folder was reported as "out of memory".
  const std::string folder_buffer = gltf_with_nodes("folder.gltf", ",\"nodes\":[{\"mesh\":0}]");
  const fs::path folder = fs::path(folder_buffer).parent_path();
  std::string json;
  {
    std::ifstream in(folder_buffer);
    json.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  fs::create_directory(folder / "sub");
  const std::string to_folder = (folder / "to_folder.gltf").string();
  write_file(to_folder, std::string(json).replace(json.find("mesh.bin"), 8, "sub"));
  EXPECT_TRUE(LoadFails(to_folder, ErrorCode::kIo, "path", {"sub", "is a directory"}));

  // A buffer URI naming a file larger than the buffer: refused before it is read.
  const std::string big = (folder / "big.bin").string();
  fs::resize_file(fs::path(write_and_return(big, "")), std::uintmax_t{64} << 20);  // sparse
  const std::string to_big = (folder / "to_big.gltf").string();
  write_file(to_big, std::string(json).replace(json.find("mesh.bin"), 8, "big.bin"));
  EXPECT_TRUE(LoadFails(to_big, ErrorCode::kIo, "path",
                        {"big.bin",
                         "has 67108864 bytes, more than the 36 bytes that the glTF "
                         "buffers' byteLength leave to read"}));
  EXPECT_LT(largest_allocation([&] { load_mesh(to_big); }), std::size_t{1} << 20);

  // Images are not decoded, and a huge one is not read either.
  const std::string with_big_image = (folder / "big_image.gltf").string();
  write_file(with_big_image,
             json.substr(0, json.size() - 1) + ",\"images\":[{\"uri\":\"big.bin\"}]}");
  EXPECT_EQ(load_mesh(with_big_image).vertex_count(), 3u);
  EXPECT_LT(largest_allocation([&] { load_mesh(with_big_image); }), std::size_t{1} << 20);

  // An image URI naming a FIFO: images are not needed, the load must not wait for it.
  const std::string fifo = (folder / "texture.png").string();
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const std::string with_image = (folder / "image.gltf").string();
  write_file(with_image,
             json.substr(0, json.size() - 1) + ",\"images\":[{\"uri\":\"texture.png\"}]}");
  EXPECT_TRUE(FinishesWithin(
      10, [&] { EXPECT_EQ(load_mesh(with_image).vertex_count(), 3u); },
      [&] { release_fifo_reader(fifo); }));
}

}  // namespace
}  // namespace finflex
