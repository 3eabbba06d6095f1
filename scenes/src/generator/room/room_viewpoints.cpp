// Viewpoints: where cameras and light probes may stand. Sampled uniformly in the room and
// kept when valid (room_layout.h's rules) and spread out; the most open one is the camera.
#include <algorithm>
#include <cmath>
#include <limits>

#include "generator/room/room_plan_steps.h"
#include "phyir/core/safe_math.h"
#include "phyir/scenes/room_layout.h"

namespace phyir::scenes {

namespace {

float distance_to_segment(glm::vec2 p, glm::vec2 a, glm::vec2 b) {
  const glm::vec2 ab = b - a;
  const float t = std::clamp(glm::dot(p - a, ab) / glm::dot(ab, ab), 0.0f, 1.0f);
  return glm::length(p - (a + t * ab));
}

// Distance to the nearest wall or object: how open the view from p is.
float clearance(const RoomLayout& layout, const glm::vec3& p) {
  const std::vector<glm::vec2> corners = layout.shell.outline();
  float nearest = std::numeric_limits<float>::max();
  for (size_t i = 0; i < corners.size(); ++i) {
    nearest = std::min(nearest, distance_to_segment({p.x, p.z}, corners[i], corners[(i + 1) % corners.size()]));
  }
  for (const RoomObject& object : layout.objects) nearest = std::min(nearest, object.bounds.distance_to(p));
  return nearest;
}

// Rounded to millimetres: the glTF file prints them exactly, so a point read back from the
// file is the point that was checked here.
float to_millimetres(float metres) { return std::round(metres * 1000.0f) / 1000.0f; }

glm::vec3 sample_point(const RoomLayout& layout, Pcg32& rng) {
  const float x = rng.uniform(-0.5f * layout.shell.width, 0.5f * layout.shell.width);
  const float y = rng.uniform(kViewpointMinHeight, kViewpointMaxHeight);
  const float z = rng.uniform(-0.5f * layout.shell.depth, 0.5f * layout.shell.depth);
  return {to_millimetres(x), to_millimetres(y), to_millimetres(z)};
}

// A level view direction for the camera: of 16 headings, the one that sees the most floor
// furniture (centres within 0.7 rad, about the horizontal half-field of yfov 1.2 at 3:2),
// ties going to the longest look across the room. Returns a point 1 m away that way.
glm::vec3 aim_camera(const RoomLayout& layout, const glm::vec3& eye) {
  constexpr int kHeadings = 16;
  constexpr float kHalfView = 0.7f;
  glm::vec2 best_dir(0.0f, -1.0f);
  int best_seen = -1;
  float best_reach = -1.0f;
  for (int k = 0; k < kHeadings; ++k) {
    const float yaw = kTwoPi * static_cast<float>(k) / kHeadings;
    const glm::vec2 dir(std::sin(yaw), std::cos(yaw));
    int seen = 0;
    for (const RoomObject& object : layout.objects) {
      if (object.mount != Mount::Floor) continue;
      const glm::vec3 c = object.bounds.centre();
      const glm::vec2 to(c.x - eye.x, c.z - eye.z);
      if (glm::dot(to, dir) > std::cos(kHalfView) * glm::length(to)) ++seen;
    }
    float reach = 0.0f;  // to the wall, in 5 cm steps
    while (layout.shell.contains(glm::vec2(eye.x, eye.z) + (reach + 0.05f) * dir, 0.0f)) reach += 0.05f;
    if (seen > best_seen || (seen == best_seen && reach > best_reach)) {
      best_seen = seen;
      best_reach = reach;
      best_dir = dir;
    }
  }
  return eye + glm::vec3(best_dir.x, 0.0f, best_dir.y);
}

}  // namespace

bool is_valid_viewpoint(const RoomLayout& layout, const glm::vec3& p) {
  if (!(p.y >= kViewpointMinHeight && p.y <= kViewpointMaxHeight)) return false;
  if (p.y > layout.shell.height - kViewpointClearance) return false;
  if (!layout.shell.contains({p.x, p.z}, kViewpointClearance)) return false;
  for (const RoomObject& object : layout.objects) {
    if (object.bounds.distance_to(p) < kViewpointClearance) return false;
  }
  return true;
}

bool plan_viewpoints(RoomLayout& layout, Pcg32 rng) {
  const size_t needed = 1 + kMinCandidateViewpoints;
  const size_t wanted = layout.preset == RoomPreset::Hard ? 16 : 12;
  std::vector<glm::vec3> points;
  // Prefer points 60 cm apart; accept 25 cm in crowded rooms rather than too few.
  for (const float spacing : {0.6f, 0.25f}) {
    for (int attempt = 0; attempt < 4000 && points.size() < wanted; ++attempt) {
      const glm::vec3 p = sample_point(layout, rng);
      if (!is_valid_viewpoint(layout, p)) continue;
      const bool crowded = std::any_of(points.begin(), points.end(),
                                       [&](const glm::vec3& q) { return glm::distance(p, q) < spacing; });
      if (!crowded) points.push_back(p);
    }
    if (points.size() >= needed) break;
  }
  if (points.size() < needed) return false;

  size_t camera = 0;
  for (size_t i = 1; i < points.size(); ++i) {
    if (clearance(layout, points[i]) > clearance(layout, points[camera])) camera = i;
  }
  layout.camera_position = points[camera];
  layout.camera_target = aim_camera(layout, points[camera]);
  layout.candidate_viewpoints.clear();
  for (size_t i = 0; i < points.size(); ++i) {
    if (i != camera) layout.candidate_viewpoints.push_back(points[i]);
  }
  return true;
}

}  // namespace phyir::scenes
