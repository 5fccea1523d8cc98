#include "finflex/level_choice.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>

#include <glm/gtc/matrix_transform.hpp>

#include "cl/device_buffers.hpp"
#include "finflex/error.hpp"

namespace finflex {

namespace {

constexpr std::size_t kViewFloats = 32;  // kernels/lod/choose_levels.cl: two float16 a view

[[noreturn]] void invalid(const std::string& field, const std::string& why) {
  throw Error(ErrorCode::kInvalidArgument, field, field + ": " + why);
}

bool finite(const glm::dmat4& m) {
  for (int c = 0; c < 4; ++c) {
    for (int r = 0; r < 4; ++r) {
      if (!std::isfinite(m[c][r])) return false;
    }
  }
  return true;
}

// A view as the kernel reads it: the six frustum planes of clip_from_view *
// view_from_world (rows combined as for OpenGL's -w <= x, y, z <= w), each scaled to a
// unit normal; the depth row (minus the view's z row); the near plane; the focal length.
std::array<double, kViewFloats> view_record(const LevelView& view) {
  const glm::dmat4 m = view.clip_from_view * view.view_from_world;
  const auto row = [&](int r) { return glm::dvec4(m[0][r], m[1][r], m[2][r], m[3][r]); };
  const glm::dvec4 w = row(3);
  const glm::dvec4 planes[6] = {w + row(0), w - row(0), w + row(1),
                                w - row(1), w + row(2), w - row(2)};
  std::array<double, kViewFloats> out{};
  for (int q = 0; q < 6; ++q) {
    const double norm = glm::length(glm::dvec3(planes[q]));
    for (int c = 0; c < 4; ++c) out[std::size_t(4 * q + c)] = planes[q][c] / norm;
  }
  const glm::dmat4& v = view.view_from_world;
  for (int c = 0; c < 4; ++c) out[std::size_t(24 + c)] = -v[c][2];
  out[28] = view.near_plane();
  out[29] = view.focal_pixels;
  return out;
}

// A kernel's arguments, in order.
template <typename... Values>
void set_arguments(cl::Kernel& kernel, const Values&... values) {
  cl_uint arg = 0;
  (check_cl(kernel.setArg(arg++, values), "clSetKernelArg"), ...);
}

void check_views(const std::vector<LevelView>& views) {
  if (views.empty() || views.size() > kMaxLevelViews) {
    invalid("views", std::to_string(views.size()) + " views: 1 to " +
                         std::to_string(kMaxLevelViews) + " are taken");
  }
  for (std::size_t w = 0; w < views.size(); ++w)
    views[w].validate("views[" + std::to_string(w) + "]");
}

// The coarsest level within each budget for a body length of `pixels_per_length`.
int level_for(const std::vector<double>& errors, double pixels_per_length,
              const LevelChoiceOptions& options, int previous) {
  int within = 0, within_keep = 0;
  const double keep = options.pixel_budget * (1.0 - options.hysteresis);
  for (std::size_t k = 1; k < errors.size(); ++k) {
    const double pixels = errors[k] * pixels_per_length;
    if (pixels <= options.pixel_budget) within = int(k);
    if (pixels <= keep) within_keep = int(k);
  }
  if (previous < 0 || within < previous) return within;
  return std::max(previous, within_keep);
}

}  // namespace

LevelView LevelView::look_at(const glm::dvec3& eye, const glm::dvec3& target, const glm::dvec3& up,
                             double vertical_fov_degrees, int width, int height, double near_plane,
                             double far_plane) {
  if (!(vertical_fov_degrees > 0.0 && vertical_fov_degrees < 180.0)) {
    invalid("vertical_fov_degrees", std::to_string(vertical_fov_degrees) + " is not in (0, 180)");
  }
  if (width <= 0 || height <= 0) {
    invalid("size", std::to_string(width) + "x" + std::to_string(height) + " is not positive");
  }
  LevelView view;
  view.view_from_world = glm::lookAt(eye, target, up);
  const double fov = glm::radians(vertical_fov_degrees);
  view.clip_from_view =
      glm::perspective(fov, double(width) / double(height), near_plane, far_plane);
  view.focal_pixels = double(height) / (2.0 * std::tan(0.5 * fov));
  view.validate("view");
  return view;
}

double LevelView::near_plane() const {
  // OpenGL's perspective: z_clip = a z + b, w_clip = -z, so the near plane (z_ndc = -1)
  // is at depth b / (a - 1).
  return clip_from_view[3][2] / (clip_from_view[2][2] - 1.0);
}

glm::dvec3 LevelView::eye() const {
  const glm::dmat3 r(view_from_world);
  return -(glm::transpose(r) * glm::dvec3(view_from_world[3]));
}

void LevelView::validate(const std::string& field) const {
  if (!finite(view_from_world)) invalid(field + ".view_from_world", "not finite");
  if (!finite(clip_from_view)) invalid(field + ".clip_from_view", "not finite");
  const glm::dmat3 r(view_from_world);
  const glm::dmat3 error = glm::transpose(r) * r - glm::dmat3(1.0);
  double worst = 0.0;
  for (int c = 0; c < 3; ++c) {
    for (int k = 0; k < 3; ++k) worst = std::max(worst, std::abs(error[c][k]));
  }
  if (worst > 1e-6 || glm::determinant(r) < 0.0 || view_from_world[0][3] != 0.0 ||
      view_from_world[1][3] != 0.0 || view_from_world[2][3] != 0.0 ||
      view_from_world[3][3] != 1.0) {
    invalid(field + ".view_from_world", "not a rigid motion (rotation and translation)");
  }
  const glm::dmat4& p = clip_from_view;
  if (p[0][3] != 0.0 || p[1][3] != 0.0 || p[2][3] != -1.0 || p[3][3] != 0.0) {
    invalid(field + ".clip_from_view", "not a perspective projection (w_clip = -z_view)");
  }
  const double n = near_plane();
  const double f = p[3][2] / (p[2][2] + 1.0);
  if (!(n > 0.0 && f > n)) {
    invalid(field + ".clip_from_view",
            "near " + std::to_string(n) + ", far " + std::to_string(f) + ": not 0 < near < far");
  }
  if (!(std::isfinite(focal_pixels) && focal_pixels > 0.0)) {
    invalid(field + ".focal_pixels", std::to_string(focal_pixels) + " is not > 0");
  }
}

void LevelChoiceOptions::validate() const {
  if (!(std::isfinite(pixel_budget) && pixel_budget > 0.0)) {
    invalid("pixel_budget", std::to_string(pixel_budget) + " is not > 0");
  }
  if (!(hysteresis >= 0.0 && hysteresis < 1.0)) {
    invalid("hysteresis", std::to_string(hysteresis) + " is not in [0, 1)");
  }
}

BodyBounds body_bounds(const RiggedMesh& model, double margin) {
  if (!(std::isfinite(margin) && margin > 0.0)) {
    invalid("margin", std::to_string(margin) + " is not > 0");
  }
  const BodyFrame& root = model.rig().components.front().frame;
  glm::dvec3 low(std::numeric_limits<double>::infinity());
  glm::dvec3 high(-std::numeric_limits<double>::infinity());
  for (const glm::vec3& p : model.mesh().positions) {
    const glm::dvec3 local = root.point_to_local(glm::dvec3(p));
    low = glm::min(low, local);
    high = glm::max(high, local);
  }
  BodyBounds out;
  out.centre = 0.5 * (low + high);
  for (const glm::vec3& p : model.mesh().positions) {
    out.radius = std::max(out.radius, glm::length(root.point_to_local(glm::dvec3(p)) - out.centre));
  }
  out.radius *= 1.0 + margin;
  return out;
}

std::vector<double> level_errors(const DetailLevels& levels) {
  const double length = levels.level(0).model.rig().components.front().frame.length;
  std::vector<double> out;
  for (const DetailLevel& level : levels.levels()) out.push_back(level.geometric_error / length);
  return out;
}

int choose_level_on_host(const PlacementRecord& r, const BodyBounds& bounds,
                         const std::vector<double>& errors, const std::vector<LevelView>& views,
                         const LevelChoiceOptions& options, int previous,
                         const std::vector<WallOccluder>& occluders) {
  const glm::dvec3 centre = glm::dvec3(r[9], r[10], r[11]) +
                            bounds.centre.x * glm::dvec3(r[0], r[1], r[2]) +
                            bounds.centre.y * glm::dvec3(r[3], r[4], r[5]) +
                            bounds.centre.z * glm::dvec3(r[6], r[7], r[8]);
  const double length = 1.0 / double(r[12]);
  const double radius = length * bounds.radius;
  double pixels_per_length = -1.0;
  for (const LevelView& view : views) {
    const std::array<double, kViewFloats> v = view_record(view);
    bool inside = true;
    for (std::size_t q = 0; q < 6; ++q) {
      const double distance =
          v[4 * q] * centre.x + v[4 * q + 1] * centre.y + v[4 * q + 2] * centre.z + v[4 * q + 3];
      inside = inside && distance >= -radius;
    }
    if (!inside) continue;
    const glm::dvec3 eye = view.eye();
    const auto hides = [&](const WallOccluder& wall) {
      return wall_hides_sphere(eye, centre, radius, wall);
    };
    if (std::any_of(occluders.begin(), occluders.end(), hides)) continue;
    const double depth = v[24] * centre.x + v[25] * centre.y + v[26] * centre.z + v[27] - radius;
    pixels_per_length = std::max(pixels_per_length, length * v[29] / std::max(depth, v[28]));
  }
  if (pixels_per_length < 0.0) return -1;
  return level_for(errors, pixels_per_length, options, previous);
}

struct LevelChooser::Impl {
  Context& context;
  std::size_t levels;
  std::size_t capacity;
  std::size_t group;
  LevelChoiceOptions options;
  BodyBounds bounds;
  std::size_t last_instances = 0;
  std::vector<std::size_t> rows, firsts;  // per level: its list's rows and first entry
  cl::Buffer errors, index_counts, level_rows, own_counts, level_of, group_counts, group_starts,
      lists, counts, draw_arguments;
  cl::Buffer walls;  // two float4 a wall (lod/wall_occlusion.cl), room for one at least
  std::size_t wall_count = 0;
  cl::Kernel choose, offsets, scatter;

  Impl(Context& c, const DetailLevels& detail, std::size_t instances, const LevelChoiceOptions& o)
      : context(c), levels(detail.size()), capacity(instances), options(o) {
    const std::size_t device_group = context.device().getInfo<CL_DEVICE_MAX_WORK_GROUP_SIZE>();
    group = 1;
    while (group * 2 <= std::min<std::size_t>(256, device_group)) group *= 2;
    bounds = body_bounds(detail.level(0).model);
    const cl::Context& cl_context = context.context();
    std::vector<float> error_values;
    std::vector<cl_uint> index_values;
    const std::vector<double> in_body_lengths = level_errors(detail);
    for (std::size_t k = 0; k < levels; ++k) {
      error_values.push_back(float(in_body_lengths[k]));
      index_values.push_back(cl_uint(detail.level(k).triangle_count * 3));
    }
    errors = detail::make_buffer(cl_context, CL_MEM_READ_ONLY, levels * sizeof(float),
                                 error_values.data());
    rows = options.level_rows.empty() ? std::vector<std::size_t>(levels, capacity)
                                      : options.level_rows;
    std::vector<cl_uint> row_values;
    std::size_t first = 0;
    for (std::size_t k = 0; k < levels; ++k) {
      firsts.push_back(first);
      first += rows[k];
      row_values.push_back(cl_uint(rows[k]));
    }
    for (std::size_t k = 0; k < levels; ++k) row_values.push_back(cl_uint(firsts[k]));
    level_rows = detail::make_buffer(cl_context, CL_MEM_READ_ONLY, 2 * levels * sizeof(cl_uint),
                                     row_values.data());
    own_counts = detail::make_buffer(cl_context, CL_MEM_READ_WRITE, levels * sizeof(cl_uint));
    index_counts = detail::make_buffer(cl_context, CL_MEM_READ_ONLY, levels * sizeof(cl_uint),
                                       index_values.data());
    const std::vector<cl_int> none(capacity, -1);
    level_of =
        detail::make_buffer(cl_context, CL_MEM_READ_WRITE, capacity * sizeof(cl_int), none.data());
    const std::size_t groups = (capacity + group - 1) / group;
    group_counts =
        detail::make_buffer(cl_context, CL_MEM_READ_WRITE, groups * levels * sizeof(cl_uint));
    group_starts =
        detail::make_buffer(cl_context, CL_MEM_READ_WRITE, groups * levels * sizeof(cl_uint));
    lists = detail::make_buffer(cl_context, CL_MEM_READ_WRITE, first * sizeof(cl_uint));
    // No instance of any level until the first choice.
    const std::vector<cl_uint> zeros(5 * levels, 0);
    counts = detail::make_buffer(cl_context, CL_MEM_READ_WRITE, (levels + 1) * sizeof(cl_uint),
                                 zeros.data());
    draw_arguments = detail::make_buffer(cl_context, CL_MEM_READ_WRITE,
                                         5 * levels * sizeof(cl_uint), zeros.data());
    walls = detail::make_buffer(cl_context, CL_MEM_READ_ONLY, 2 * sizeof(cl_float4));
    const ProgramSource source{{"lod/wall_occlusion.cl", "lod/choose_levels.cl"},
                               "#define FF_LOD_GROUP " + std::to_string(group) +
                                   "\n#define FF_LOD_LEVELS " + std::to_string(levels) + "\n",
                               ""};
    choose = context.kernel("lod_choose", source, "");
    offsets = context.kernel("lod_offsets", source, "");
    scatter = context.kernel("lod_scatter", source, "");
  }
};

LevelChooser::LevelChooser(Context& context, const DetailLevels& levels, std::size_t capacity,
                           const LevelChoiceOptions& options) {
  options.validate();
  if (levels.size() > kMaxChosenLevels) {
    invalid("levels", std::to_string(levels.size()) + " levels, more than the " +
                          std::to_string(kMaxChosenLevels) + " a choice takes");
  }
  if (capacity == 0 || capacity > std::size_t(std::numeric_limits<cl_int>::max())) {
    invalid("capacity", std::to_string(capacity) + " is not 1 to 2^31 - 1 instances");
  }
  const std::vector<std::size_t>& rows = options.level_rows;
  if (!rows.empty() && rows.size() != levels.size()) {
    invalid("level_rows", std::to_string(rows.size()) + " entries for " +
                              std::to_string(levels.size()) + " levels");
  }
  std::size_t all_rows = 0;
  for (std::size_t k = 0; k < rows.size(); ++k) {
    if (rows[k] == 0 || rows[k] > capacity) {
      invalid("level_rows[" + std::to_string(k) + "]",
              std::to_string(rows[k]) + " is not 1 to the capacity " + std::to_string(capacity));
    }
    all_rows += rows[k];
  }
  if (all_rows > 0xffffffffu) invalid("level_rows", "more than 2^32 rows in all");
  impl_ = std::make_unique<Impl>(context, levels, capacity, options);
}

LevelChooser::~LevelChooser() = default;

std::size_t LevelChooser::level_count() const { return impl_->levels; }
std::size_t LevelChooser::capacity() const { return impl_->capacity; }
std::size_t LevelChooser::rows(std::size_t level) const { return impl_->rows.at(level); }
std::size_t LevelChooser::list_first(std::size_t level) const { return impl_->firsts.at(level); }
const cl::Buffer& LevelChooser::levels() const { return impl_->level_of; }
const cl::Buffer& LevelChooser::lists() const { return impl_->lists; }
const cl::Buffer& LevelChooser::counts() const { return impl_->counts; }
const cl::Buffer& LevelChooser::draw_arguments() const { return impl_->draw_arguments; }

std::size_t LevelChooser::occluder_count() const { return impl_->wall_count; }

void LevelChooser::set_occluders(const std::vector<WallOccluder>& occluders) {
  for (std::size_t w = 0; w < occluders.size(); ++w) {
    occluders[w].validate("occluders[" + std::to_string(w) + "]");
  }
  Impl& d = *impl_;
  std::vector<cl_float4> packed;
  for (const WallOccluder& wall : occluders) {
    packed.push_back(
        {{float(wall.base.x), float(wall.base.y), float(wall.base.z), float(wall.height)}});
    packed.push_back({{float(wall.radius), float(wall.inner_radius()), 0.0f, 0.0f}});
  }
  if (!packed.empty()) {
    d.walls = detail::make_buffer(d.context.context(), CL_MEM_READ_ONLY,
                                  packed.size() * sizeof(cl_float4), packed.data());
  }
  d.wall_count = occluders.size();
}

void LevelChooser::forget() {
  Impl& d = *impl_;
  const cl_int none = -1;
  check_cl(d.context.queue().enqueueFillBuffer(d.level_of, none, 0, d.capacity * sizeof(cl_int)),
           "clEnqueueFillBuffer");
}

cl::Event LevelChooser::enqueue(const cl::Buffer& placements, std::size_t instances,
                                const std::vector<LevelView>& views,
                                const std::vector<cl::Event>* wait,
                                std::vector<cl::Event>* kernels) {
  Impl& d = *impl_;
  if (instances > d.capacity) {
    invalid("instances",
            std::to_string(instances) + " is above the capacity " + std::to_string(d.capacity));
  }
  const std::size_t held = placements.getInfo<CL_MEM_SIZE>() / (kPlacementFloats * sizeof(float));
  if (instances > held) {
    invalid("instances",
            std::to_string(instances) + " instances: the placements hold " + std::to_string(held));
  }
  check_views(views);
  std::array<cl_float16, 2 * kMaxLevelViews> packed{};
  std::array<cl_float4, kMaxLevelViews> eyes{};
  for (std::size_t w = 0; w < views.size(); ++w) {
    const glm::dvec3 eye = views[w].eye();
    eyes[w] = {{float(eye.x), float(eye.y), float(eye.z), 0.0f}};
    const std::array<double, kViewFloats> record = view_record(views[w]);
    for (std::size_t k = 0; k < 16; ++k) {
      packed[2 * w].s[k] = float(record[k]);
      packed[2 * w + 1].s[k] = float(record[16 + k]);
    }
  }
  d.last_instances = instances;
  const std::size_t groups = std::max<std::size_t>(1, (instances + d.group - 1) / d.group);
  const cl_float4 bounds{{float(d.bounds.centre.x), float(d.bounds.centre.y),
                          float(d.bounds.centre.z), float(d.bounds.radius)}};
  set_arguments(
      d.choose, placements, cl_uint(instances), bounds, d.errors, packed[0], packed[1], packed[2],
      packed[3], packed[4], packed[5], packed[6], packed[7], eyes[0], eyes[1], eyes[2], eyes[3],
      cl_uint(views.size()), d.walls, cl_uint(d.wall_count), float(d.options.pixel_budget),
      float(d.options.pixel_budget * (1.0 - d.options.hysteresis)), d.level_of, d.group_counts);
  set_arguments(d.offsets, d.group_counts, cl_uint(groups), d.group_starts, d.index_counts,
                d.level_rows, d.own_counts, d.counts, d.draw_arguments);
  set_arguments(d.scatter, d.level_of, cl_uint(instances), d.group_starts, d.level_rows,
                d.own_counts, d.lists);
  cl::CommandQueue& queue = d.context.queue();
  const cl::NDRange local(d.group);
  const cl::NDRange global(groups * d.group);
  cl::Event chosen, placed, done;
  check_cl(queue.enqueueNDRangeKernel(d.choose, cl::NullRange, global, local, wait, &chosen),
           "clEnqueueNDRangeKernel lod_choose");
  check_cl(queue.enqueueNDRangeKernel(d.offsets, cl::NullRange, local, local, nullptr, &placed),
           "clEnqueueNDRangeKernel lod_offsets");
  check_cl(queue.enqueueNDRangeKernel(d.scatter, cl::NullRange, global, local, nullptr, &done),
           "clEnqueueNDRangeKernel lod_scatter");
  if (kernels) *kernels = {chosen, placed, done};
  return done;
}

LevelChooser::Choice LevelChooser::read(bool with_levels) {
  Impl& d = *impl_;
  cl::CommandQueue& queue = d.context.queue();
  Choice out;
  out.level_of.resize(with_levels ? d.last_instances : 0);
  std::vector<cl_uint> counts(d.levels + 1);
  out.draw_arguments.resize(5 * d.levels);
  if (!out.level_of.empty()) {
    check_cl(queue.enqueueReadBuffer(d.level_of, CL_TRUE, 0, d.last_instances * sizeof(cl_int),
                                     out.level_of.data()),
             "clEnqueueReadBuffer");
  }
  check_cl(
      queue.enqueueReadBuffer(d.counts, CL_TRUE, 0, counts.size() * sizeof(cl_uint), counts.data()),
      "clEnqueueReadBuffer");
  out.undrawn = counts[d.levels];
  check_cl(queue.enqueueReadBuffer(d.draw_arguments, CL_TRUE, 0, 5 * d.levels * sizeof(cl_uint),
                                   out.draw_arguments.data()),
           "clEnqueueReadBuffer");
  for (std::size_t k = 0; k < d.levels; ++k) {
    std::vector<std::uint32_t> list(std::min<std::size_t>(counts[k], d.rows[k]));
    if (!list.empty()) {
      check_cl(queue.enqueueReadBuffer(d.lists, CL_TRUE, d.firsts[k] * sizeof(cl_uint),
                                       list.size() * sizeof(cl_uint), list.data()),
               "clEnqueueReadBuffer");
    }
    out.lists.push_back(std::move(list));
  }
  return out;
}

}  // namespace finflex
