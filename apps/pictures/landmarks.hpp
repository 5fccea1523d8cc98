// The points a fish is measured between: the tip of the snout and the fork of the tail
// (fork length, the length fisheries measure), and where the rig names the parts, the
// caudal fin's upper and lower tips and each pectoral fin's tip. All are vertices of the
// rest mesh, so their deformed positions come straight from the engine's output.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "finflex/model.hpp"

namespace finflex::pictures {

// The dataset's keypoints, in this order for every species (COCO's and YOLO's): a
// species whose rig lacks a part has no such keypoint (visibility 0). A horizontal flip
// swaps the pectoral fins (kKeypointFlip).
constexpr std::size_t kKeypointCount = 6;
constexpr std::array<const char*, kKeypointCount> kKeypointNames{"snout",
                                                                 "tail_fork",
                                                                 "caudal_upper_tip",
                                                                 "caudal_lower_tip",
                                                                 "left_pectoral_tip",
                                                                 "right_pectoral_tip"};
constexpr std::array<std::size_t, kKeypointCount> kKeypointFlip{0, 1, 2, 3, 5, 4};
constexpr std::size_t kSpinePoints = 16;  // from the snout to the tail fork

// The rig component each keypoint comes from (none: the snout and the tail fork, from
// the whole mesh).
constexpr std::array<const char*, kKeypointCount> kKeypointParts{
    "", "", "caudal_fin", "caudal_fin", "left_pectoral_fin", "right_pectoral_fin"};

// The keypoints named (kKeypointNames), as indices in that order whatever the names',
// for a dataset that annotates only those. finflex::Error (kInvalidArgument) naming
// `option` for a name that is not a keypoint, a name twice, or one pectoral tip without
// the other (a horizontal flip swaps them).
std::vector<std::size_t> chosen_keypoints(const std::vector<std::string>& names,
                                          const std::string& option);

struct FishLandmarks {
  std::uint32_t snout = 0;      // mesh vertex index
  std::uint32_t tail_fork = 0;  // mesh vertex index
  // Per keypoint (kKeypointNames) its mesh vertex, none where the rig has no such part.
  std::array<std::optional<std::uint32_t>, kKeypointCount> keypoints;
  // (x_snout - x_fork) / s_x: the fork length as a fraction of the total length (the
  // body frame's s_x, the length a placement scales to), straight rest pose.
  double fork_fraction = 1.0;
  // The spine, kSpinePoints stations from the snout to the tail fork, equally spaced
  // along the straight rest body: each the midpoint of two vertices (the snout and the
  // fork: the vertex itself twice).
  std::array<std::array<std::uint32_t, 2>, kSpinePoints> spine{};
};

// In the rig root's frame (e_x towards the head, e_y dorsal, lengths in body lengths):
//   snout: the vertex farthest forward (largest x);
//   tail fork: among the rearmost fifth of the body (x < x_min + 0.2), the vertices
//     within 5 % of the body length of the tail's mid-height (the middle of the
//     rearmost tenth's y range), the rearmost one: where the trailing edge of the
//     caudal fin crosses its middle, the fork's notch on a forked tail and the tip on
//     a round one;
//   caudal tips: of the vertices of the component named "caudal_fin", the most dorsal
//     (largest y) and the most ventral (smallest y);
//   pectoral tips: of the vertices of "left_pectoral_fin" ("right_pectoral_fin"), the
//     farthest from the component's frame origin (its attachment to the body);
//   spine: between them, at each station the highest and the lowest vertex of the
//     body (the root component's own vertices: no fin) within a fifth of a station's
//     spacing, else of any part (over the caudal fin), else the nearest vertex: on the
//     fish's plane of symmetry, their midpoint follows the midline as the body bends.
FishLandmarks find_landmarks(const RiggedMesh& model);

// The rest mesh's vertices in the rig root's frame, in body lengths (e_x towards the
// head, e_y dorsal).
std::vector<glm::dvec3> rest_in_body_frame(const RiggedMesh& model);

// Per mesh vertex, its place on the body, for the renderer's painted albedo
// (render::Renderer::add_mesh): u = (x_max - x) / (x_max - x_min), 0 at the snout and
// 1 at the tail; v = 2 (y - y_low) / (y_high - y_low) - 1, y_low and y_high the lowest
// and highest vertex of its station (one of 32 equal slices along x), -1 the belly and
// 1 the back (or the tips of the fins that stand out of them).
std::vector<glm::vec2> body_pattern(const RiggedMesh& model);

}  // namespace finflex::pictures
