// Room shell: the floor plan (rectangle or L), its walls, and axis-aligned boxes.
#include <algorithm>
#include <cmath>

#include "generator/room/room_plan_steps.h"
#include "phyir/scenes/room_layout.h"

namespace phyir::scenes {

bool Box3::overlaps(const Box3& other, float gap) const {
  for (int a = 0; a < 3; ++a) {
    if (min[a] >= other.max[a] + gap || other.min[a] >= max[a] + gap) return false;
  }
  return true;
}

float Box3::distance_to(const glm::vec3& p) const {
  const glm::vec3 outside = glm::max(glm::max(min - p, p - max), glm::vec3(0.0f));
  return glm::length(outside);
}

void Box3::extend(const Box3& other) {
  min = glm::min(min, other.min);
  max = glm::max(max, other.max);
}

std::vector<glm::vec2> RoomShell::outline() const {
  const float x0 = -0.5f * width, x1 = 0.5f * width;
  const float z0 = -0.5f * depth, z1 = 0.5f * depth;
  if (!l_shaped) return {{x0, z0}, {x1, z0}, {x1, z1}, {x0, z1}};
  // The notch takes the (+x, +z) corner; corner 3 is the reflex one (see fan_corner()).
  return {{x0, z0}, {x1, z0}, {x1, notch_min.y}, {notch_min.x, notch_min.y}, {notch_min.x, z1}, {x0, z1}};
}

glm::vec2 RoomShell::wall_inward_normal(int wall) const {
  const std::vector<glm::vec2> corners = outline();
  const glm::vec2 a = corners[wall];
  const glm::vec2 b = corners[(wall + 1) % corners.size()];
  const glm::vec2 along = glm::normalize(b - a);
  const glm::vec2 left(-along.y, along.x);
  // Walls are axis-aligned: a point 1 cm to one side of the midpoint tells inside from out.
  return contains(0.5f * (a + b) + 0.01f * left, 0.0f) ? left : -left;
}

bool RoomShell::contains(glm::vec2 xz, float margin) const { return contains(xz, xz, margin); }

bool RoomShell::contains(glm::vec2 min_xz, glm::vec2 max_xz, float margin) const {
  if (min_xz.x < -0.5f * width + margin || max_xz.x > 0.5f * width - margin) return false;
  if (min_xz.y < -0.5f * depth + margin || max_xz.y > 0.5f * depth - margin) return false;
  if (!l_shaped) return true;
  // Outside the notch grown by the margin (a square grow: conservative at its corner).
  const bool clear_of_notch = max_xz.x <= notch_min.x - margin || max_xz.y <= notch_min.y - margin;
  return clear_of_notch;
}

RoomShell plan_shell(Pcg32& rng, RoomPreset preset) {
  RoomShell shell;
  if (preset != RoomPreset::Hard) {
    shell.width = rng.uniform(3.0f, 4.5f);
    shell.depth = rng.uniform(3.0f, 4.5f);
    shell.height = rng.uniform(2.4f, 2.8f);
    return shell;
  }
  shell.width = rng.uniform(4.5f, 7.0f);
  shell.depth = rng.uniform(4.5f, 7.0f);
  shell.height = rng.uniform(2.6f, 3.2f);
  shell.l_shaped = rng.chance(0.6f);
  if (shell.l_shaped) {
    // The notch takes 35-50% of each side, so both arms stay at least 2.2 m wide.
    const float notch_w = shell.width * rng.uniform(0.35f, 0.5f);
    const float notch_d = shell.depth * rng.uniform(0.35f, 0.5f);
    shell.notch_min = {0.5f * shell.width - notch_w, 0.5f * shell.depth - notch_d};
    shell.notch_max = {0.5f * shell.width, 0.5f * shell.depth};
  }
  return shell;
}

}  // namespace phyir::scenes
