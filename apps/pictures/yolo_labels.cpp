#include "yolo_labels.hpp"

#include <cstdio>
#include <deque>
#include <limits>

namespace finflex::pictures {

namespace {

// The pixels of one id within a box, with each pixel's 4-connected part.
struct BoxPixels {
  int x0 = 0, y0 = 0, width = 0, height = 0;
  std::vector<int> part;  // -1: not the id's; else its part, numbered in raster order

  bool inside(int x, int y) const {
    if (x < x0 || y < y0 || x >= x0 + width || y >= y0 + height) return false;
    return part[std::size_t(y - y0) * std::size_t(width) + std::size_t(x - x0)] >= 0;
  }
};

// Labels the id's parts; `starts` gets each part's first pixel in raster order (its
// top edge's left end is on the outer boundary: nothing of the part is above it).
BoxPixels label_parts(const render::IdImage& ids, const InstanceMask& mask,
                      std::vector<glm::ivec2>& starts) {
  BoxPixels box;
  box.x0 = mask.x_min;
  box.y0 = mask.y_min;
  box.width = mask.x_max - mask.x_min + 1;
  box.height = mask.y_max - mask.y_min + 1;
  const std::size_t pixels = std::size_t(box.width) * std::size_t(box.height);
  box.part.assign(pixels, -1);
  std::vector<bool> mine(pixels, false);
  for (int y = 0; y < box.height; ++y) {
    for (int x = 0; x < box.width; ++x) {
      mine[std::size_t(y) * std::size_t(box.width) + std::size_t(x)] =
          ids.ids[ids.index(box.x0 + x, box.y0 + y)] == mask.id;
    }
  }
  std::deque<glm::ivec2> queue;
  int parts = 0;
  for (int y = 0; y < box.height; ++y) {
    for (int x = 0; x < box.width; ++x) {
      const std::size_t at = std::size_t(y) * std::size_t(box.width) + std::size_t(x);
      if (!mine[at] || box.part[at] >= 0) continue;
      starts.push_back({box.x0 + x, box.y0 + y});
      box.part[at] = parts;
      queue.push_back({x, y});
      while (!queue.empty()) {
        const glm::ivec2 p = queue.front();
        queue.pop_front();
        const glm::ivec2 next[4] = {{p.x + 1, p.y}, {p.x - 1, p.y}, {p.x, p.y + 1}, {p.x, p.y - 1}};
        for (const glm::ivec2& q : next) {
          if (q.x < 0 || q.y < 0 || q.x >= box.width || q.y >= box.height) continue;
          const std::size_t k = std::size_t(q.y) * std::size_t(box.width) + std::size_t(q.x);
          if (!mine[k] || box.part[k] >= 0) continue;
          box.part[k] = parts;
          queue.push_back(q);
        }
      }
      ++parts;
    }
  }
  return box;
}

// The outer boundary of the part whose first pixel is `start`, along pixel edges with
// the part on the right (y down): straight on while the pixel ahead on the right is the
// part's and the one ahead on the left is not, left where both are, right where the
// right one is not (so parts touching at a corner stay apart: 4-connectivity).
std::vector<glm::dvec2> trace(const BoxPixels& box, glm::ivec2 start) {
  const int part = box.part[std::size_t(start.y - box.y0) * std::size_t(box.width) +
                            std::size_t(start.x - box.x0)];
  const auto of_part = [&](int x, int y) {
    return box.inside(x, y) &&
           box.part[std::size_t(y - box.y0) * std::size_t(box.width) + std::size_t(x - box.x0)] ==
               part;
  };
  // The pixel of the unit square beside the edge from corner c along d, on side s.
  const auto square = [&](glm::ivec2 c, glm::ivec2 d, glm::ivec2 s) {
    return glm::min(glm::min(c, c + d), glm::min(c + s, c + d + s));
  };
  std::vector<glm::dvec2> out{glm::dvec2(start)};
  glm::ivec2 corner = start;
  glm::ivec2 direction{1, 0};
  corner += direction;
  for (;;) {
    const glm::ivec2 right{-direction.y, direction.x};
    const glm::ivec2 ahead_right = square(corner, direction, right);
    const glm::ivec2 ahead_left = square(corner, direction, -right);
    glm::ivec2 next = direction;
    if (!of_part(ahead_right.x, ahead_right.y)) {
      next = right;
    } else if (of_part(ahead_left.x, ahead_left.y)) {
      next = -right;
    }
    if (corner == start && next == glm::ivec2(1, 0)) break;
    if (next != direction) out.push_back(glm::dvec2(corner));
    direction = next;
    corner += direction;
  }
  return out;
}

// Joins `part` into `polygon` at their nearest points: there, around the part, back.
void join(std::vector<glm::dvec2>& polygon, const std::vector<glm::dvec2>& part) {
  std::size_t best_p = 0, best_q = 0;
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    for (std::size_t j = 0; j < part.size(); ++j) {
      const glm::dvec2 d = polygon[i] - part[j];
      const double distance = glm::dot(d, d);
      if (distance < best) {
        best = distance;
        best_p = i;
        best_q = j;
      }
    }
  }
  std::vector<glm::dvec2> joined(polygon.begin(), polygon.begin() + long(best_p) + 1);
  for (std::size_t k = 0; k <= part.size(); ++k) joined.push_back(part[(best_q + k) % part.size()]);
  joined.insert(joined.end(), polygon.begin() + long(best_p), polygon.end());
  polygon = std::move(joined);
}

void append_number(std::string& line, double value) {
  char text[32];
  std::snprintf(text, sizeof text, " %.6f", value);
  line += text;
}

}  // namespace

const char* to_string(YoloTask task) {
  switch (task) {
    case YoloTask::kSegment:
      return "segment";
    case YoloTask::kPose:
      return "pose";
    case YoloTask::kDetect:
      break;
  }
  return "detect";
}

std::vector<glm::dvec2> mask_outline(const render::IdImage& ids, const InstanceMask& mask) {
  std::vector<glm::ivec2> starts;
  const BoxPixels box = label_parts(ids, mask, starts);
  std::vector<glm::dvec2> polygon;
  for (const glm::ivec2& start : starts) {
    const std::vector<glm::dvec2> part = trace(box, start);
    if (polygon.empty()) {
      polygon = part;
    } else {
      join(polygon, part);
    }
  }
  return polygon;
}

std::string yolo_line(YoloTask task, std::size_t category, const InstanceMask& mask,
                      const std::vector<glm::dvec2>& outline,
                      const std::vector<std::array<double, 3>>& keypoints, int width, int height) {
  const double w = width, h = height;
  std::string line = std::to_string(category);
  if (task == YoloTask::kSegment) {
    for (const glm::dvec2& p : outline) {
      append_number(line, p.x / w);
      append_number(line, p.y / h);
    }
    return line;
  }
  // The box in pixel edges: pixels x_min..x_max cover [x_min, x_max + 1).
  const double x0 = mask.x_min, x1 = mask.x_max + 1.0, y0 = mask.y_min, y1 = mask.y_max + 1.0;
  append_number(line, 0.5 * (x0 + x1) / w);
  append_number(line, 0.5 * (y0 + y1) / h);
  append_number(line, (x1 - x0) / w);
  append_number(line, (y1 - y0) / h);
  if (task == YoloTask::kPose) {
    for (const auto& [u, v, visibility] : keypoints) {
      append_number(line, visibility > 0 ? u / w : 0.0);
      append_number(line, visibility > 0 ? v / h : 0.0);
      line += " " + std::to_string(int(visibility));
    }
  }
  return line;
}

std::string yolo_dataset_yaml(YoloTask task, const std::vector<std::string>& names,
                              const std::vector<std::string>& keypoint_names,
                              const std::vector<std::size_t>& flip) {
  std::string out = "# FinFlex swim dataset for Ultralytics YOLO (" + std::string(to_string(task)) +
                    "): images/ and labels/ beside this file\n";
  out += "train: images\nval: images\nnames:\n";
  for (std::size_t c = 0; c < names.size(); ++c) {
    out += "  " + std::to_string(c) + ": " + names[c] + "\n";
  }
  if (task == YoloTask::kPose) {
    out += "kpt_shape: [" + std::to_string(keypoint_names.size()) + ", 3]\nflip_idx: [";
    for (std::size_t k = 0; k < flip.size(); ++k) out += (k ? ", " : "") + std::to_string(flip[k]);
    out += "]\n# keypoints:";
    for (const std::string& name : keypoint_names) out += " " + name;
    out += "\n";
  }
  return out;
}

}  // namespace finflex::pictures
