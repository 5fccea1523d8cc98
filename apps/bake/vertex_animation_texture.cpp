#include "vertex_animation_texture.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>

#include <nlohmann/json.hpp>

#include "gltf_builder.hpp"
#include "render/png16.hpp"

namespace finflex::bake {

namespace {

namespace fs = std::filesystem;

std::uint16_t quantise(double unit) {  // unit in [0, 1]
  return static_cast<std::uint16_t>(std::lround(std::clamp(unit, 0.0, 1.0) * 65535.0));
}

// The frames' positions (mode 0) or normals (mode 1) as a 16-bit RGB image.
render::Image16 encode(const BakedCycle& baked, const VatLayout& layout, bool normals) {
  const DeformedBatch<float>& batch = baked.batch;
  render::Image16 image;
  image.width = static_cast<int>(layout.width);
  image.height = static_cast<int>(layout.height);
  image.channels = 3;
  image.samples.assign(layout.width * layout.height * 3, 0);
  const glm::dvec3 lo(layout.bounds_min);
  const glm::dvec3 range = glm::dvec3(layout.bounds_max) - lo;
  for (std::size_t k = 0; k < baked.cycle.frames; ++k) {
    for (std::size_t v = 0; v < batch.shape.vertex_count; ++v) {
      const std::size_t row = k * layout.rows_per_frame + v / layout.width;
      std::uint16_t* texel = image.samples.data() + (row * layout.width + v % layout.width) * 3;
      const glm::dvec3 value =
          normals ? glm::dvec3(batch.normal(k, v)) : glm::dvec3(batch.position(k, v));
      for (int c = 0; c < 3; ++c) {
        const double unit =
            normals ? 0.5 * value[c] + 0.5 : (range[c] > 0.0 ? (value[c] - lo[c]) / range[c] : 0.0);
        texel[c] = quantise(unit);
      }
    }
  }
  return image;
}

std::string glsl(const std::string& stem, const VatLayout& layout, const BakedCycle& baked) {
  const auto number = [](double value) {
    char text[40];
    std::snprintf(text, sizeof text, "%.9g", value);
    std::string s = text;
    if (s.find_first_of(".e") == std::string::npos) s += ".0";
    return s;
  };
  const auto vec3 = [&](const glm::vec3& v) {
    return "vec3(" + number(v.x) + ", " + number(v.y) + ", " + number(v.z) + ")";
  };
  return "// Decoding the FinFlex vertex animation textures " + stem +
         "_vat_*.png (GLSL 3.30 / ES 3.00).\n"
         "// Bind them as 16-bit unsigned normalised RGB, linear (not sRGB), nearest, no mipmaps.\n"
         "uniform sampler2D vat_positions;\n"
         "uniform sampler2D vat_normals;\n"
         "const int VAT_WIDTH = " +
         std::to_string(layout.width) +
         ";\n"
         "const int VAT_ROWS_PER_FRAME = " +
         std::to_string(layout.rows_per_frame) +
         ";\n"
         "const int VAT_FRAMES = " +
         std::to_string(baked.cycle.frames) +
         ";\n"
         "const float VAT_PERIOD = " +
         number(baked.cycle.period_s) +
         ";  // seconds: one tail beat\n"
         "const vec3 VAT_BOUNDS_MIN = " +
         vec3(layout.bounds_min) +
         ";\n"
         "const vec3 VAT_BOUNDS_MAX = " +
         vec3(layout.bounds_max) +
         ";\n"
         "\n"
         "ivec2 vat_texel(int vertex, int frame) {\n"
         "  return ivec2(vertex % VAT_WIDTH, frame * VAT_ROWS_PER_FRAME + vertex / VAT_WIDTH);\n"
         "}\n"
         "vec3 vat_position(int vertex, int frame) {  // metres, the head towards +z, y up\n"
         "  vec3 q = texelFetch(vat_positions, vat_texel(vertex, frame), 0).rgb;  // q / 65535\n"
         "  return VAT_BOUNDS_MIN + q * (VAT_BOUNDS_MAX - VAT_BOUNDS_MIN);\n"
         "}\n"
         "vec3 vat_normal(int vertex, int frame) {\n"
         "  return normalize(texelFetch(vat_normals, vat_texel(vertex, frame), 0).rgb * 2.0 - "
         "1.0);\n"
         "}\n"
         "// The pose at time t (seconds), looping, blended between the two nearest frames.\n"
         "void vat_pose(int vertex, float t, out vec3 position, out vec3 normal) {\n"
         "  float f = fract(t / VAT_PERIOD) * float(VAT_FRAMES);\n"
         "  int f0 = int(f) % VAT_FRAMES;\n"
         "  int f1 = (f0 + 1) % VAT_FRAMES;\n"
         "  float w = fract(f);\n"
         "  position = mix(vat_position(vertex, f0), vat_position(vertex, f1), w);\n"
         "  normal = normalize(mix(vat_normal(vertex, f0), vat_normal(vertex, f1), w));\n"
         "}\n"
         "// In a vertex shader: vat_pose(gl_VertexID, time, p, n); or, without vertex ids,\n"
         "// vertex = int(TEXCOORD_1.y) * VAT_WIDTH + int(TEXCOORD_1.x * float(VAT_WIDTH)).\n";
}

void write_text(const fs::path& path, const std::string& text) {
  const fs::path temporary = path.string() + ".partial";
  std::ofstream out(temporary, std::ios::binary);
  out << text;
  out.close();
  std::error_code ec;
  if (!out) throw Error(ErrorCode::kIo, "path", "'" + path.string() + "': write failed");
  fs::rename(temporary, path, ec);
  if (ec) throw Error(ErrorCode::kIo, "path", "'" + path.string() + "': " + ec.message());
}

// The rest pose with the lookup coordinates in TEXCOORD_1.
void write_mesh(const fs::path& path, const std::string& name, const Mesh& mesh,
                const BakedCycle& baked, const VatLayout& layout) {
  const DeformedBatch<float>& batch = baked.batch;
  const std::size_t rest = baked.cycle.frames;
  std::vector<glm::vec3> positions(batch.shape.vertex_count), normals(positions.size());
  std::vector<glm::vec2> lookup(positions.size());
  for (std::size_t v = 0; v < positions.size(); ++v) {
    positions[v] = batch.position(rest, v);
    normals[v] = batch.normal(rest, v);
    lookup[v] = {(double(v % layout.width) + 0.5) / double(layout.width), double(v / layout.width)};
  }
  GltfBuilder gltf;
  tinygltf::Primitive primitive;
  primitive.mode = TINYGLTF_MODE_TRIANGLES;
  primitive.attributes["POSITION"] = gltf.add_vec3(positions, true);
  primitive.attributes["NORMAL"] = gltf.add_vec3(normals, false);
  primitive.attributes["TEXCOORD_0"] =
      gltf.add_vec2(mesh.texcoords.empty() ? lookup : mesh.texcoords);
  primitive.attributes["TEXCOORD_1"] = gltf.add_vec2(lookup);
  primitive.indices = gltf.add_indices(mesh.indices);
  gltf.set_mesh(name, primitive);
  gltf.write_glb(path.string());
}

}  // namespace

VatLayout vat_layout(const BakedCycle& baked, std::size_t max_width) {
  if (max_width == 0 || max_width > 16384) {
    throw Error(ErrorCode::kInvalidArgument, "max_width",
                "--vat-width " + std::to_string(max_width) + " (expected 1 to 16384)");
  }
  const std::size_t vertices = baked.batch.shape.vertex_count;
  VatLayout layout;
  layout.width = std::min(vertices, max_width);
  layout.rows_per_frame = (vertices + layout.width - 1) / layout.width;
  layout.height = layout.rows_per_frame * baked.cycle.frames;
  glm::vec3 lo(std::numeric_limits<float>::infinity());
  glm::vec3 hi(-std::numeric_limits<float>::infinity());
  for (std::size_t k = 0; k < baked.cycle.frames; ++k) {
    for (std::size_t v = 0; v < vertices; ++v) {
      lo = glm::min(lo, baked.batch.position(k, v));
      hi = glm::max(hi, baked.batch.position(k, v));
    }
  }
  layout.bounds_min = lo;
  layout.bounds_max = hi;
  return layout;
}

VatLayout write_vertex_animation_texture(const std::string& folder, const std::string& stem,
                                         const Mesh& mesh, const BakedCycle& baked,
                                         std::size_t max_width) {
  const VatLayout layout = vat_layout(baked, max_width);
  const fs::path base(folder);
  const auto file = [&](const char* suffix) { return base / (stem + suffix); };
  render::write_png16(file("_vat_positions.png").string(), encode(baked, layout, false));
  render::write_png16(file("_vat_normals.png").string(), encode(baked, layout, true));
  write_text(file("_vat.glsl"), glsl(stem, layout, baked));
  write_mesh(file("_vat_mesh.glb"), stem, mesh, baked, layout);

  const auto vec = [](const glm::vec3& v) {
    return nlohmann::ordered_json{double(v.x), double(v.y), double(v.z)};
  };
  nlohmann::ordered_json json;
  json["vertex_count"] = baked.batch.shape.vertex_count;
  json["frames"] = baked.cycle.frames;
  json["period_s"] = baked.cycle.period_s;
  json["frame_dt_s"] = baked.cycle.dt_s;
  json["texture_width"] = layout.width;
  json["texture_height"] = layout.height;
  json["rows_per_frame"] = layout.rows_per_frame;
  json["bounds_min"] = vec(layout.bounds_min);
  json["bounds_max"] = vec(layout.bounds_max);
  json["position_texture"] = stem + "_vat_positions.png";
  json["normal_texture"] = stem + "_vat_normals.png";
  json["mesh"] = stem + "_vat_mesh.glb";
  json["glsl"] = stem + "_vat.glsl";
  json["texel"] =
      "vertex v of frame k: (v mod texture_width, k rows_per_frame + floor(v / texture_width))";
  json["position"] = "bounds_min + (q / 65535) (bounds_max - bounds_min), q the 16-bit sample";
  json["normal"] = "normalize(2 q / 65535 - 1)";
  json["position_error_max"] = vec((layout.bounds_max - layout.bounds_min) / 131070.0f);
  json["texture_format"] = "16-bit RGB PNG; linear data (not sRGB), nearest filtering, no mipmaps";
  json["units"] = "metres; y up; the head towards +z; the pivot at the origin";
  write_text(file("_vat.json"), json.dump(1) + "\n");
  return layout;
}

}  // namespace finflex::bake
