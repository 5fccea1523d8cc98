#include "landmarks.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "finflex/error.hpp"

namespace finflex::pictures {

std::vector<std::size_t> chosen_keypoints(const std::vector<std::string>& names,
                                          const std::string& option) {
  std::array<bool, kKeypointCount> chosen{};
  for (const std::string& name : names) {
    const auto found = std::find(kKeypointNames.begin(), kKeypointNames.end(), name);
    if (found == kKeypointNames.end()) {
      std::string known;
      for (const char* keypoint : kKeypointNames) {
        known += (known.empty() ? "" : ", ") + std::string(keypoint);
      }
      throw Error(ErrorCode::kInvalidArgument, option,
                  option + ": '" + name + "' is not a keypoint (" + known + ")");
    }
    const auto k = std::size_t(found - kKeypointNames.begin());
    if (chosen[k]) {
      throw Error(ErrorCode::kInvalidArgument, option, option + ": '" + name + "' twice");
    }
    chosen[k] = true;
  }
  if (chosen[4] != chosen[5]) {
    throw Error(ErrorCode::kInvalidArgument, option,
                option +
                    ": left_pectoral_tip and right_pectoral_tip go together (a horizontal "
                    "flip swaps them)");
  }
  std::vector<std::size_t> out;
  for (std::size_t k = 0; k < kKeypointCount; ++k) {
    if (chosen[k]) out.push_back(k);
  }
  return out;
}

std::vector<glm::dvec3> rest_in_body_frame(const RiggedMesh& model) {
  const Mesh& mesh = model.mesh();
  const BodyFrame& frame = model.rig().components.front().frame;  // the root's
  std::vector<glm::dvec3> local(mesh.vertex_count());
  for (std::size_t v = 0; v < local.size(); ++v) {
    const glm::dvec3 d = glm::dvec3(mesh.positions[v]) - frame.origin;
    local[v] = glm::dvec3(glm::dot(d, frame.axis_x), glm::dot(d, frame.axis_y),
                          glm::dot(d, frame.axis_z)) /
               frame.length;
  }
  return local;
}

std::vector<glm::vec2> body_pattern(const RiggedMesh& model) {
  const std::vector<glm::dvec3> local = rest_in_body_frame(model);
  double x_min = std::numeric_limits<double>::infinity();
  double x_max = -x_min;
  for (const glm::dvec3& p : local) {
    x_min = std::min(x_min, p.x);
    x_max = std::max(x_max, p.x);
  }
  constexpr int kStations = 32;
  const double span = std::max(x_max - x_min, 1e-12);
  const auto station = [&](double x) {
    return std::clamp(static_cast<int>((x_max - x) / span * kStations), 0, kStations - 1);
  };
  std::vector<double> low(kStations, std::numeric_limits<double>::infinity());
  std::vector<double> high(kStations, -std::numeric_limits<double>::infinity());
  for (const glm::dvec3& p : local) {
    const int s = station(p.x);
    low[s] = std::min(low[s], p.y);
    high[s] = std::max(high[s], p.y);
  }
  std::vector<glm::vec2> pattern(local.size());
  for (std::size_t v = 0; v < local.size(); ++v) {
    const int s = station(local[v].x);
    const double height = std::max(high[s] - low[s], 1e-12);
    pattern[v] = glm::vec2(static_cast<float>((x_max - local[v].x) / span),
                           static_cast<float>(2.0 * (local[v].y - low[s]) / height - 1.0));
  }
  return pattern;
}

FishLandmarks find_landmarks(const RiggedMesh& model) {
  const Mesh& mesh = model.mesh();
  const std::vector<glm::dvec3> local = rest_in_body_frame(model);
  FishLandmarks marks;
  double x_min = std::numeric_limits<double>::infinity();
  double x_max = -x_min;
  for (std::size_t v = 0; v < local.size(); ++v) {
    x_min = std::min(x_min, local[v].x);
    if (local[v].x > x_max) {
      x_max = local[v].x;
      marks.snout = static_cast<std::uint32_t>(v);
    }
  }
  double y_low = std::numeric_limits<double>::infinity();
  double y_high = -y_low;
  for (const glm::dvec3& p : local) {
    if (p.x < x_min + 0.1) {
      y_low = std::min(y_low, p.y);
      y_high = std::max(y_high, p.y);
    }
  }
  const double mid_height = 0.5 * (y_low + y_high);
  double rearmost = std::numeric_limits<double>::infinity();
  for (std::size_t v = 0; v < local.size(); ++v) {
    const glm::dvec3& p = local[v];
    if (p.x < x_min + 0.2 && std::fabs(p.y - mid_height) < 0.05 && p.x < rearmost) {
      rearmost = p.x;
      marks.tail_fork = static_cast<std::uint32_t>(v);
    }
  }
  // With no vertex in the band (a tail too sparse), the rearmost vertex stands in.
  if (!std::isfinite(rearmost)) {
    for (std::size_t v = 0; v < local.size(); ++v) {
      if (local[v].x == x_min) marks.tail_fork = static_cast<std::uint32_t>(v);
    }
  }
  marks.fork_fraction = x_max - local[marks.tail_fork].x;  // local lengths are in s_x
  const std::vector<std::uint32_t>& body = model.rig().components.front().vertices;
  const double x_snout = x_max, x_fork = local[marks.tail_fork].x;
  const double spacing = (x_snout - x_fork) / double(kSpinePoints - 1);
  marks.spine.front() = {marks.snout, marks.snout};
  marks.spine.back() = {marks.tail_fork, marks.tail_fork};
  for (std::size_t s = 1; s + 1 < kSpinePoints; ++s) {
    const double x = x_snout - double(s) * spacing;
    std::optional<std::uint32_t> high, low;
    std::uint32_t nearest = marks.snout;
    const auto consider = [&](std::uint32_t v) {
      if (std::fabs(local[v].x - x) < std::fabs(local[nearest].x - x)) nearest = v;
      if (std::fabs(local[v].x - x) > 0.2 * spacing) return;
      if (!high || local[v].y > local[*high].y) high = v;
      if (!low || local[v].y < local[*low].y) low = v;
    };
    for (std::uint32_t v : body) consider(v);
    if (!high) {  // past the body's own vertices (over the caudal fin), or no rig parts
      for (std::uint32_t v = 0; v < local.size(); ++v) consider(v);
    }
    marks.spine[s] = high ? std::array<std::uint32_t, 2>{*high, *low}
                          : std::array<std::uint32_t, 2>{nearest, nearest};
  }
  marks.keypoints[0] = marks.snout;
  marks.keypoints[1] = marks.tail_fork;
  for (const RigComponent& component : model.rig().components) {
    if (component.vertices.empty()) continue;
    const auto by = [&](auto score) {
      std::uint32_t best = component.vertices.front();
      for (std::uint32_t v : component.vertices) {
        if (score(v) > score(best)) best = v;
      }
      return best;
    };
    const auto from_attachment = [&](std::uint32_t v) {
      return glm::length(glm::dvec3(mesh.positions[v]) - component.frame.origin);
    };
    if (component.name == kKeypointParts[2]) {  // the caudal fin's tips
      marks.keypoints[2] = by([&](std::uint32_t v) { return local[v].y; });
      marks.keypoints[3] = by([&](std::uint32_t v) { return -local[v].y; });
    } else if (component.name == kKeypointParts[4]) {
      marks.keypoints[4] = by(from_attachment);
    } else if (component.name == kKeypointParts[5]) {
      marks.keypoints[5] = by(from_attachment);
    }
  }
  return marks;
}

}  // namespace finflex::pictures
