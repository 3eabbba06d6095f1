#include "phyir/scenes/triangle_corners.h"

#include <algorithm>
#include <cstring>
#include <functional>

namespace phyir::scenes {

namespace {

bool lexicographic_less(const glm::vec3& a, const glm::vec3& b) {
  if (a.x != b.x) return a.x < b.x;
  if (a.y != b.y) return a.y < b.y;
  return a.z < b.z;
}

}  // namespace

TriangleCorners::TriangleCorners(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c) : sorted{a, b, c} {
  std::sort(sorted.begin(), sorted.end(), lexicographic_less);
}

size_t TriangleCornersHash::operator()(const TriangleCorners& corners) const {
  size_t h = 0;
  for (const glm::vec3& p : corners.sorted) {
    for (int k = 0; k < 3; ++k) {
      // -0 and +0 compare equal, so they must hash equal: hash their sum with 0.
      const float value = p[k] + 0.0f;
      uint32_t bits = 0;
      std::memcpy(&bits, &value, sizeof bits);
      h = h * 0x100000001B3ull ^ std::hash<uint32_t>()(bits);
    }
  }
  return h;
}

}  // namespace phyir::scenes
