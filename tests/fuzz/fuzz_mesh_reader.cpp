// libFuzzer harness: the reader of one format (FINFLEX_FUZZ_FORMAT, a MeshFormat
// enumerator) as load_mesh runs it (io::read_mesh_bytes: read, normals, validation)
// on the fuzzer's bytes. Relative glTF URIs resolve against FINFLEX_FUZZ_BASE_DIR.
//
// Findings: crashes and sanitizer reports, inputs slower than -timeout, memory beyond
// -rss_limit_mb or -malloc_limit_mb, and broken contracts, which abort with a line
// on stderr:
// - the only exception is finflex::Error, with code kIo, kFormat or kInvalidMesh, a
//   field, and a message of printable ASCII (text from the file cannot reach a
//   terminal raw) that names the field (or, for field "path", the file);
// - a mesh that loads has vertices, passes validate_mesh, has unit normals for every
//   vertex, and face groups that lie in order within its triangles.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>
#include <string_view>

#include "finflex/error.hpp"
#include "finflex/mesh.hpp"
#include "io/formats.hpp"

namespace {

using finflex::ErrorCode;

[[noreturn]] void broken(const std::string& what) {
  std::fprintf(stderr, "contract broken: %s\n", what.c_str());
  std::abort();
}

void check_mesh(const finflex::Mesh& mesh) {
  if (mesh.vertex_count() == 0) broken("a loaded mesh without vertices");
  try {
    finflex::validate_mesh(mesh);
  } catch (const finflex::Error& error) {
    broken(std::string("a loaded mesh fails validation: ") + error.what());
  }
  if (mesh.normals.size() != mesh.vertex_count()) broken("normals missing after loading");
  for (const glm::vec3& n : mesh.normals) {
    const float length = glm::length(n);
    if (!(std::fabs(length - 1.0f) < 1e-3f)) {
      broken("a normal of length " + std::to_string(length));
    }
  }
  std::size_t next = 0;
  for (const finflex::FaceGroup& group : mesh.groups) {
    if (group.name.empty() || group.triangle_count == 0 || group.first_triangle < next ||
        group.first_triangle + group.triangle_count > mesh.triangle_count()) {
      broken("face group '" + group.name + "' out of order or out of range");
    }
    next = group.first_triangle + group.triangle_count;
  }
}

void check_error(const finflex::Error& error) {
  const ErrorCode code = error.code();
  if (code != ErrorCode::kIo && code != ErrorCode::kFormat && code != ErrorCode::kInvalidMesh) {
    broken(std::string("error code ") + finflex::error_code_name(code) + ": " + error.what());
  }
  const std::string message = error.what();
  if (error.field().empty() || message.empty()) broken("an error without field or message");
  for (const char c : message) {
    if (c < 0x20 || c > 0x7e)
      broken("a byte that is not printable ASCII in the message: " + message);
  }
  if (error.field() != "path" && message.find(error.field()) == std::string::npos) {
    broken("the message does not name the field '" + error.field() + "': " + message);
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  try {
    check_mesh(finflex::io::read_mesh_bytes(bytes, finflex::io::MeshFormat::FINFLEX_FUZZ_FORMAT,
                                            FINFLEX_FUZZ_BASE_DIR));
  } catch (const finflex::Error& error) {
    check_error(error);
  } catch (const std::exception& error) {
    broken(std::string("an exception that is not a finflex::Error: ") + error.what());
  }
  return 0;
}
