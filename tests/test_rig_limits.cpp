// Rigs of any size and shape: deep JSON values, huge values quoted in messages, rigs
// nested thousands of levels deep or thousands of components wide, hand-made rigs
// with cycles, rig files that are not regular files. Each is refused with a message
// naming the limit or the problem, or resolved in time following its size; never a
// crash, a hang or an allocation out of proportion.
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <functional>
#include <future>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "finflex/error.hpp"
#include "finflex/model.hpp"
#include "finflex/rig.hpp"
#include "support/synthetic_fish.hpp"
#include "support/test_support.hpp"

namespace finflex {
namespace {

// The error `call` throws (or a failure when it throws nothing).
template <typename Call>
Error error_of(Call call) {
  try {
    call();
  } catch (const Error& e) {
    return e;
  }
  ADD_FAILURE() << "nothing thrown";
  return Error(ErrorCode::kInvalidArgument, "", "");
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

std::string component(const std::string& name, const std::string& parent, const std::string& select,
                      const std::string& chain) {
  std::string text = "{\"name\": \"" + name + "\"";
  if (!parent.empty()) text += ", \"parent\": \"" + parent + "\"";
  if (!parent.empty()) text += ", \"frame\": {\"mode\": \"identity\"}";
  return text + ", \"select\": " + select + ", \"chain\": " + chain + "}";
}

std::string hinge(const std::string& param) {
  return "[{\"deformer\": \"hinge\", \"param\": \"" + param + "\"}]";
}

// A chain c0 <- c1 <- ... <- c(n-1), each selecting all of its parent with a hinge.
std::string nested_rig(std::size_t n) {
  std::string text = "{\"frame\": {\"mode\": \"identity\"}, \"components\": [" +
                     component("c0", "", "\"all\"", "[]");
  for (std::size_t i = 1; i < n; ++i) {
    text += ", " + component("c" + std::to_string(i), "c" + std::to_string(i - 1), "\"all\"",
                             hinge("a" + std::to_string(i)));
  }
  return text + "]}";
}

// ---------------------------------------------------------------------------------
// JSON values

TEST(RigJsonLimits, DeeplyNestedValuesAreRefusedNamingTheLimit) {
  const std::size_t deep = 200000;
  const std::string open(deep, '['), close(deep, ']');
  std::string objects;
  for (std::size_t k = 0; k < deep; ++k) objects += "{\"a\": ";
  objects += "1" + std::string(deep, '}');
  for (const std::string& text :
       {"{\"frame\": " + open + close + "}", open + close,
        "{\"components\": [{\"name\": \"b\", \"select\": " + open + close + "}]}",
        "{\"components\": [" + objects + "]}"}) {
    const Error e = error_of([&] { parse_rig_json(text); });
    EXPECT_NE(std::string(e.what()).find("nested deeper than 64 levels"), std::string::npos)
        << std::string(e.what()).substr(0, 200);
    EXPECT_NE(std::string(e.what()).find("kMaxRigJsonDepth"), std::string::npos);
  }
  const Error e = error_of([&] { parse_rig_json("{\"frame\": " + open + close + "}"); });
  EXPECT_EQ(e.code(), ErrorCode::kInvalidArgument);
  EXPECT_EQ(e.field().rfind("frame[0][0]", 0), 0u) << e.field();
}

TEST(RigJsonLimits, ValuesUpToTheLimitAreQuotedLikeJsonDumpsThem) {
  // 63 levels below the top-level object: accepted by the parser, refused by the schema
  // with the value quoted (shortened).
  const std::string text = "{\"frame\": " + std::string(63, '[') + std::string(63, ']') + "}";
  const Error e = error_of([&] { parse_rig_json(text); });
  EXPECT_EQ(e.field(), "frame");
  EXPECT_NE(std::string(e.what()).find("frame = " + std::string(63, '[') + std::string(14, ']') +
                                       "...: expected an object"),
            std::string::npos)
      << e.what();
  const Error small = error_of([&] {
    parse_rig_json(R"({"frame": {"origin": [1, 2.5, "x"], "x": [1, 0, 0], "y": null}})");
  });
  EXPECT_NE(std::string(small.what()).find("frame.origin = [1,2.5,\"x\"]: expected"),
            std::string::npos)
      << small.what();
  const Error object =
      error_of([&] { parse_rig_json(R"({"components": {"b": [true, {"k": null}], "a": {}}})"); });
  EXPECT_NE(std::string(object.what()).find("{\"a\":{},\"b\":[true,{\"k\":null}]}"),
            std::string::npos)
      << object.what();
}

TEST(RigJsonLimits, AHugeValueInAMessageIsCutWithoutWritingItAll) {
  std::string text = "{\"frame\": [";
  const std::size_t elements = 2000000;
  text.reserve(elements * 2 + 32);
  for (std::size_t i = 0; i < elements; ++i) text += i ? ",1" : "1";
  text += "]}";
  const Error e = error_of([&] { parse_rig_json(text); });
  const std::string message = e.what();
  EXPECT_LT(message.size(), 300u) << message.substr(0, 300);
  EXPECT_NE(message.find("frame = [1,1,1,"), std::string::npos) << message;
  EXPECT_NE(message.find("...: expected an object"), std::string::npos) << message;
  // A long string with multi-byte characters is cut at a character boundary.
  std::string fish = "a";
  for (int i = 0; i < 100; ++i) fish += "\xc3\xa9";  // e acute
  const Error name = error_of([&] { parse_rig_json("{\"frame\": \"" + fish + "\"}"); });
  const std::string quoted = name.what();
  const std::size_t begin = quoted.find("= \"") + 3, end = quoted.find("...");
  ASSERT_NE(end, std::string::npos) << quoted;
  EXPECT_EQ((end - begin - 1) % 2, 0u) << quoted;  // whole two-byte characters only
}

// ---------------------------------------------------------------------------------
// Rig trees

TEST(RigTreeLimits, ThousandsOfNestedComponentsAreRefusedNamingTheDepthLimit) {
  const Mesh mesh = test::synthetic_fish(12, 8);
  const auto start = std::chrono::steady_clock::now();
  const RigSpec spec = parse_rig_json(nested_rig(50000));
  const Error e = error_of([&] { resolve_rig(spec, mesh); });
  EXPECT_EQ(e.code(), ErrorCode::kInvalidArgument);
  EXPECT_EQ(e.field(), "components[65] 'c65'.parent");
  EXPECT_NE(std::string(e.what()).find("at most 64 levels (kMaxRigDepth)"), std::string::npos)
      << e.what();
  EXPECT_LT(seconds_since(start), 60.0);
}

// The faster of two parses of `text`, in seconds.
double parse_seconds(const std::string& text) {
  double best = 1e9;
  for (int k = 0; k < 2; ++k) {
    const auto start = std::chrono::steady_clock::now();
    parse_rig_json(text);
    best = std::min(best, seconds_since(start));
  }
  return best;
}

TEST(RigJsonLimits, ParsingTakesTimeLinearInTheFileSize) {
  // Four times the components: about four times the time. nlohmann's parser with a
  // parser callback, used before, took twelve times (25,000 components: 0.6 s;
  // 100,000: 7.3 s).
  const double small = parse_seconds(nested_rig(20000));
  const double large = parse_seconds(nested_rig(80000));
  EXPECT_LT(large, 6.0 * small + 0.05) << small << " s, then " << large << " s";
}

TEST(RigTreeLimits, NestingUpToTheLimitResolvesWithPathsAndSubtrees) {
  const Mesh mesh = test::synthetic_fish(12, 8);
  const Rig rig = resolve_rig(parse_rig_json(nested_rig(kMaxRigDepth + 1)), mesh);
  ASSERT_EQ(rig.components.size(), kMaxRigDepth + 1);
  for (std::size_t k = 0; k <= kMaxRigDepth; ++k) {
    EXPECT_EQ(rig.depth(k), k);
    EXPECT_EQ(rig.subtree_end[k], kMaxRigDepth + 1);
    EXPECT_EQ(rig.path(k).size(), k);
  }
  EXPECT_EQ(rig.components.back().vertices.size(), mesh.vertex_count());
  const RiggedMesh model(mesh, rig);
  EXPECT_EQ(model.longest_path(), kMaxRigDepth);
}

TEST(RigTreeLimits, APathOfTooManyStagesIsRefusedNamingTheLimit) {
  std::string chain = "[";
  for (std::size_t k = 0; k <= kMaxRigPathStages; ++k) {
    chain += std::string(k ? ", " : "") + "{\"deformer\": \"hinge\", \"param\": \"a\"}";
  }
  const std::string text = "{\"frame\": {\"mode\": \"identity\"}, \"components\": [" +
                           component("body", "", "\"all\"", chain + "]") + "]}";
  const Error e = error_of([&] { resolve_rig(parse_rig_json(text), test::synthetic_fish()); });
  EXPECT_EQ(e.field(), "components[0] 'body'.chain");
  EXPECT_NE(std::string(e.what()).find("257 stages: at most 256 (kMaxRigPathStages)"),
            std::string::npos)
      << e.what();
}

// Children of the root, one mesh vertex each, each with its own parameter.
std::string wide_rig(std::size_t children, const std::string& bad_parent = "") {
  std::string text = "{\"frame\": {\"mode\": \"identity\"}, \"components\": [" +
                     component("body", "", "\"all\"", hinge("m"));
  for (std::size_t i = 0; i < children; ++i) {
    const std::string parent = i + 1 == children && !bad_parent.empty() ? bad_parent : "body";
    text += ", " + component("fin" + std::to_string(i), parent,
                             "{\"indices\": [" + std::to_string(i) + "]}",
                             hinge("p" + std::to_string(i)));
  }
  return text + "]}";
}

TEST(RigTreeLimits, ThousandsOfComponentsWideResolveInTimeFollowingTheirSize) {
  const Mesh mesh = test::synthetic_fish(700, 32);  // 22,338 vertices
  const std::size_t children = 20000;
  const RigSpec spec = parse_rig_json(wide_rig(children));
  const auto start = std::chrono::steady_clock::now();
  const Rig rig = resolve_rig(spec, mesh);
  const RiggedMesh model(mesh, rig);
  EXPECT_LT(seconds_since(start), 10.0);
  ASSERT_EQ(rig.components.size(), children + 1);
  EXPECT_EQ(rig.parameters.size(), children + 1);
  EXPECT_EQ(rig.components[children].chain[0].param, children);
  EXPECT_EQ(rig.subtree_end[0], children + 1);
  EXPECT_EQ(rig.subtree_end[1], 2u);
  EXPECT_EQ(model.paths()[children].size(), 2u);
}

TEST(RigTreeLimits, MessagesListingComponentsStayShort) {
  const Mesh mesh = test::synthetic_fish(700, 32);
  const Error e = error_of([&] { resolve_rig(parse_rig_json(wide_rig(20000, "nobody")), mesh); });
  const std::string message = e.what();
  EXPECT_LT(message.size(), 500u) << message.substr(0, 500);
  EXPECT_NE(message.find("'nobody' is not a component"), std::string::npos) << message;
  EXPECT_NE(message.find("... (20001 in all)"), std::string::npos) << message;
}

// ---------------------------------------------------------------------------------
// Hand-made rigs

Rig hand_made_chain(std::size_t n, const Mesh& mesh) {
  Rig rig;
  rig.components.resize(n);
  rig.subtree_end.resize(n);
  for (std::size_t k = 0; k < n; ++k) {
    rig.components[k].name = "c" + std::to_string(k);
    rig.components[k].parent = static_cast<int>(k) - 1;
    rig.components[k].frame = BodyFrame::identity();
    rig.subtree_end[k] = n;
  }
  for (std::uint32_t v = 0; v < mesh.vertex_count(); ++v) {
    rig.components.back().vertices.push_back(v);
  }
  return rig;
}

TEST(RigTreeLimits, AHandMadeRigWithACycleIsAnErrorNotALoop) {
  const Mesh mesh = test::synthetic_fish(12, 8);
  Rig rig = hand_made_chain(4, mesh);
  rig.components[1].parent = 3;  // 1 -> 3 -> 2 -> 1
  const Error path = error_of([&] { rig.path(2); });
  EXPECT_EQ(path.field(), "components[1].parent");
  EXPECT_NE(std::string(path.what()).find("a parent comes before its children"), std::string::npos);
  EXPECT_EQ(error_of([&] { rig.depth(3); }).field(), "components[1].parent");
  const Error model = error_of([&] { RiggedMesh made(mesh, rig); });
  EXPECT_EQ(model.field(), "rig");
  EXPECT_NE(std::string(model.what()).find("components[1].parent = 3"), std::string::npos)
      << model.what();
}

TEST(RigTreeLimits, AHandMadeRigNestedTooDeepIsRefusedBeforeItsPathsAreBuilt) {
  const Mesh mesh = test::synthetic_fish(12, 8);
  const Rig rig = hand_made_chain(200000, mesh);
  EXPECT_EQ(rig.depth(199999), 199999u);  // iterative: no stack to overflow
  const auto start = std::chrono::steady_clock::now();
  const Error e = error_of([&] { RiggedMesh made(mesh, rig); });
  EXPECT_NE(std::string(e.what()).find("at most 64 (kMaxRigDepth)"), std::string::npos) << e.what();
  EXPECT_LT(seconds_since(start), 10.0);
}

TEST(RigTreeLimits, AHandMadeRigWithBadStagesIsRefused) {
  const Mesh mesh = test::synthetic_fish(12, 8);
  Rig rig = hand_made_chain(2, mesh);
  RigStage stage;
  stage.deformer = find_deformer_type("hinge");
  stage.param = 3;
  stage.frame = BodyFrame::identity();
  rig.components[1].chain.push_back(stage);
  rig.parameters.push_back(RigParameter{"a", 0, 1, 1.0, ""});
  EXPECT_NE(std::string(error_of([&] { RiggedMesh made(mesh, rig); }).what())
                .find("components[1] 'c1'.chain[0]: param = 3 is out of range"),
            std::string::npos);
  rig.components[1].chain[0].param = 0;
  rig.subtree_end[1] = 7;
  EXPECT_NE(
      std::string(error_of([&] { RiggedMesh made(mesh, rig); }).what()).find("subtree_end[1] = 7"),
      std::string::npos);
  rig.subtree_end[1] = 2;
  EXPECT_NO_THROW(RiggedMesh made(mesh, rig));
}

// ---------------------------------------------------------------------------------
// Rig files that are not regular files

// load_rig_file(path) on another thread: the error it throws, within 10 s; `unblock`
// is run when it has not returned by then (so a failing test ends).
Error load_error_within_10_s(const std::string& path, const std::function<void()>& unblock) {
  auto result =
      std::async(std::launch::async, [path] { return error_of([&] { load_rig_file(path); }); });
  if (result.wait_for(std::chrono::seconds(10)) != std::future_status::ready) {
    ADD_FAILURE() << "load_rig_file('" << path << "') still running after 10 s";
    unblock();
  }
  return result.get();
}

TEST(LoadRigFileLimits, AFifoIsRefusedWithoutWaitingForAWriter) {
  const std::string fifo = test::temp_path("rig.fifo");
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  const Error e = load_error_within_10_s(fifo, [&] {
    const int writer = open(fifo.c_str(), O_WRONLY | O_NONBLOCK);
    if (writer >= 0) close(writer);
  });
  EXPECT_EQ(e.code(), ErrorCode::kIo);
  EXPECT_EQ(e.field(), "path");
  EXPECT_NE(std::string(e.what()).find("'" + fifo + "': is a FIFO"), std::string::npos) << e.what();
}

TEST(LoadRigFileLimits, DevicesAndDirectoriesAreRefusedByTheirKind) {
  const Error zero = load_error_within_10_s("/dev/zero", [] {});
  EXPECT_EQ(zero.code(), ErrorCode::kIo);
  EXPECT_NE(std::string(zero.what()).find("is a character device, not a rig file"),
            std::string::npos)
      << zero.what();
  const std::string folder = test::temp_path("rigs");
  std::filesystem::create_directory(folder);
  EXPECT_NE(std::string(load_error_within_10_s(folder, [] {}).what()).find("is a directory"),
            std::string::npos);
  EXPECT_NE(std::string(load_error_within_10_s(test::temp_path("none.json"), [] {}).what())
                .find("cannot open a rig file for reading (No such file or directory)"),
            std::string::npos);
}

}  // namespace
}  // namespace finflex
