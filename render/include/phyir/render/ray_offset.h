#pragma once
// Robust spawn points (Waechter & Binder, "A Fast and Robust Method for Avoiding
// Self-Intersection", Ray Tracing Gems ch. 6): the hit point is moved off the surface
// along the geometric normal by a few ULPs of its own magnitude (integer steps on the
// float bits), so neither near-origin nor far-away geometry self-intersects and thin
// geometry (1 mm) does not leak.
#include <glm/glm.hpp>

namespace phyir::render {

// `p` offset to the side `n` points to (n: unit geometric normal).
glm::vec3 offset_ray_origin(const glm::vec3& p, const glm::vec3& n);

// Offset to the side of the geometric normal that `direction` leaves on.
glm::vec3 spawn_origin(const glm::vec3& p, const glm::vec3& geometric_normal, const glm::vec3& direction);

}  // namespace phyir::render
