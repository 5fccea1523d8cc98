// Each frame, on the device: which instances a camera sees and at which level of
// detail (finflex/detail_levels.hpp), compacted into per-level instance lists and
// indirect draw arguments. Nothing returns to the host.
//
//   DetailLevels levels = make_detail_levels(fish, {});
//   LevelChooser chooser(context, levels, fish_count);
//   each frame: chooser.enqueue(driver.placement_buffer(), fish_count,
//                               {LevelView::look_at(eye, target, up, 40.0, 1920, 1080,
//                               0.05, 50.0)}, &wait);
//               // chooser.lists(): level k's instances at [list_first(k), + count k)
//               // chooser.draw_arguments(): glDrawElementsIndirect's commands per level
//
// The choice, per instance (choose_level_on_host is the same on the host):
// - Its bounding sphere (body_bounds: body-local, placed with the instance's record) is
//   culled unless it meets the frustum of at least one view (sphere against the six
//   planes; conservative near the corners) where none of the walls set by
//   set_occluders hides it from the view's eye (finflex/wall_occlusion.hpp).
// - Visible, a level's error in pixels is its geometric error (body lengths) times the
//   instance's length, times the view's focal length in pixels, over the depth of the
//   sphere's nearest point (at least the near plane's), the largest over the views that
//   see it. The instance takes the coarsest level within options.pixel_budget.
// - Hysteresis: an instance that had a level goes finer as soon as its level is over
//   the budget, but coarser only to a level within pixel_budget * (1 - hysteresis), so
//   no instance goes back and forth while its error moves inside that band. Culled
//   instances (and the first frame, and after forget()) start afresh.
// - Lists hold each level's instances in ascending order: the same placements give the
//   same lists, bit for bit.
// - Room: level k's list holds at most rows(k) instances (options.level_rows; by
//   default the capacity, every level able to hold every instance). An instance past
//   its level's rows is drawn at the next coarser level with room (after that level's
//   own, in order), or at none: counts()'s last entry counts those. levels() keeps the
//   level its error asked for. Give the rows a camera needs, and the outputs of each
//   level (LevelDeformer) follow them, not the capacity.
// Cost: three small kernels over the instances (one work-item each, and one group for
// the offsets); device memory 4 bytes a list row, 4 an instance for the levels.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "finflex/context.hpp"
#include "finflex/detail_levels.hpp"
#include "finflex/export.hpp"
#include "finflex/placement.hpp"
#include "finflex/wall_occlusion.hpp"

namespace finflex {

constexpr std::size_t kMaxLevelViews = 4;
// The most levels one chooser takes (kMaxDetailLevels and a frozen-fin level fit).
constexpr std::size_t kMaxChosenLevels = 16;

struct FINFLEX_API LevelView {
  glm::dmat4 view_from_world{1.0};  // a rigid motion; the camera looks down its -z (OpenGL)
  glm::dmat4 clip_from_view{1.0};   // a perspective projection to OpenGL's clip space
  double focal_pixels = 1000.0;     // the projection's vertical focal length, in pixels

  // A camera at `eye` looking at `target` (glm::lookAt, glm::perspective), its image
  // width x height pixels and its vertical field of view.
  static LevelView look_at(const glm::dvec3& eye, const glm::dvec3& target, const glm::dvec3& up,
                           double vertical_fov_degrees, int width, int height, double near_plane,
                           double far_plane);
  // kInvalidArgument naming `field` and the part: a non-finite value, a view that is
  // not rigid, a projection that is not a perspective one with 0 < near < far, a focal
  // length not > 0.
  void validate(const std::string& field) const;
  // The near plane's depth, from the projection.
  double near_plane() const;
  // The camera's position in the world (view_from_world's inverse at the origin).
  glm::dvec3 eye() const;
};

struct FINFLEX_API LevelChoiceOptions {
  double pixel_budget = 1.0;  // > 0: the error a level may show, in pixels
  double hysteresis = 0.25;   // [0, 1)
  // Per level the most instances its list holds (each 1 to the capacity); empty: the
  // capacity for every level. Checked by LevelChooser: "level_rows" and the level.
  std::vector<std::size_t> level_rows;
  // kInvalidArgument naming "pixel_budget" or "hysteresis" and the value.
  void validate() const;
};

// A sphere in body-local coordinates (body lengths, the placement's frame) around the
// rest mesh's vertices (centred on their box), its radius grown by `margin` (> 0) for
// what the rig moves: 0.25 holds the bundled fish swimming at their rigs' limits' half.
struct BodyBounds {
  glm::dvec3 centre{0.0};
  double radius = 0.0;
};
FINFLEX_API BodyBounds body_bounds(const RiggedMesh& model, double margin = 0.25);

// Each level's error in body lengths (geometric_error over the root frame's length).
FINFLEX_API std::vector<double> level_errors(const DetailLevels& levels);

// The level an instance placed by `record` gets (-1: culled), `previous` its level in
// the frame before (-1 for none), in double precision: the device's choice in float
// agrees except where a projected error is within float's rounding of a budget.
FINFLEX_API int choose_level_on_host(const PlacementRecord& record, const BodyBounds& bounds,
                                     const std::vector<double>& errors,
                                     const std::vector<LevelView>& views,
                                     const LevelChoiceOptions& options, int previous,
                                     const std::vector<WallOccluder>& occluders = {});

class FINFLEX_API LevelChooser {
 public:
  // For up to `capacity` instances of a species whose levels are `levels` (the sphere
  // and errors from its level 0). kInvalidArgument naming "capacity" (0 or above
  // 2^31 - 1) or options.validate()'s field.
  LevelChooser(Context& context, const DetailLevels& levels, std::size_t capacity,
               const LevelChoiceOptions& options = {});
  ~LevelChooser();
  LevelChooser(const LevelChooser&) = delete;
  LevelChooser& operator=(const LevelChooser&) = delete;

  std::size_t level_count() const;
  std::size_t capacity() const;
  // Level k's list: rows(k) entries of lists() from list_first(k).
  std::size_t rows(std::size_t level) const;
  std::size_t list_first(std::size_t level) const;

  // After `wait`, the choice for the first `instances` records of `placements`
  // (kPlacementFloats floats each, e.g. ClSwimDriver::placement_buffer()) seen by
  // `views` (1..kMaxLevelViews). Returns the last kernel's event. kInvalidArgument
  // naming "instances" (above the capacity, or more than the buffer holds) or
  // "views" / "views[i]..." (validate), nothing enqueued. `kernels`, when given, gets
  // the three kernels' events (for profiling).
  cl::Event enqueue(const cl::Buffer& placements, std::size_t instances,
                    const std::vector<LevelView>& views,
                    const std::vector<cl::Event>* wait = nullptr,
                    std::vector<cl::Event>* kernels = nullptr);
  // The walls that hide instances from every later enqueue's views (none at first;
  // an empty list clears them). kInvalidArgument naming "occluders[i]..." (validate),
  // nothing changed. Cost: per instance and view that sees it, a test per wall.
  void set_occluders(const std::vector<WallOccluder>& occluders);
  std::size_t occluder_count() const;
  // The next enqueue without hysteresis (every instance chosen afresh).
  void forget();

  const cl::Buffer& levels() const;          // cl_int per instance: its level, -1 culled
  const cl::Buffer& lists() const;           // cl_uint: level k's at [list_first(k), + count k)
  const cl::Buffer& counts() const;          // cl_uint per level, then the instances drawn at none
  const cl::Buffer& draw_arguments() const;  // 5 cl_uint per level (DrawElementsIndirectCommand)

  // The last choice on the host (waits for the queue): for tests and tools; without
  // `with_levels`, level_of is left empty (the lists and counts only).
  struct Choice {
    std::vector<int> level_of;                      // per instance of the last enqueue
    std::vector<std::vector<std::uint32_t>> lists;  // per level, as its list holds them
    std::vector<std::uint32_t> draw_arguments;      // 5 per level
    std::uint32_t undrawn = 0;                      // visible, but in no level's rows
  };
  Choice read(bool with_levels = true);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace finflex
