#pragma once
// A triangle's corners in a canonical order, whatever its winding and first vertex: two
// triangles with equal TriangleCorners are coincident twins. Some models make a sheet
// double-sided by adding every triangle again wound the other way (lamp shades, doors and
// leaves of the Sweet Home 3D library); a renderer that ignores the side a ray hits needs
// only one of them, and light sampling must not count both (docs/conventions.md).
#include <glm/glm.hpp>

#include <array>
#include <cstddef>

namespace phyir::scenes {

struct TriangleCorners {
  std::array<glm::vec3, 3> sorted;  // lexicographic (x, y, z) order; exact float values

  // The corners must be finite (NaN has no order).

  TriangleCorners(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c);
  bool operator==(const TriangleCorners& other) const { return sorted == other.sorted; }
};

struct TriangleCornersHash {
  size_t operator()(const TriangleCorners& corners) const;
};

}  // namespace phyir::scenes
