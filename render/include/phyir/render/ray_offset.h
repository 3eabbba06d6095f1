#pragma once
// Robust spawn points (Waechter & Binder, "A Fast and Robust Method for Avoiding
// Self-Intersection", Ray Tracing Gems ch. 6): the hit point is moved off the surface
// along the geometric normal by a few ULPs of its own magnitude (integer steps on the
// float bits), so neither near-origin nor far-away geometry self-intersects and thin
// geometry (1 mm) does not leak.
#include <glm/glm.hpp>

#include "phyir/render/ray.h"

namespace phyir::render {

// `p` offset to the side `n` points to (n: unit geometric normal).
glm::vec3 offset_ray_origin(const glm::vec3& p, const glm::vec3& n);

// Offset to the side of the geometric normal that `direction` leaves on.
glm::vec3 spawn_origin(const glm::vec3& p, const glm::vec3& geometric_normal, const glm::vec3& direction);

// A shadow ray from `p` (geometric normal `geometric_normal`) to `target`, a point on a
// light with geometric normal `target_normal`: both ends are moved off their surfaces
// towards each other and the ray aims from one to the other. Offsetting only the origin is
// not enough: the origin's offset (256 ulps, 61 um at 2.4 m) shortens the way to the
// light's plane by offset / cos, which exceeds the kShadowRayShortening margin (1e-4 of
// the distance) whenever the light is less than ~0.6 m away there, so every such shadow
// ray hit the light itself and was counted as occluded.
Ray shadow_ray_to(const glm::vec3& p, const glm::vec3& geometric_normal, const glm::vec3& target,
                  const glm::vec3& target_normal);

// The same from an origin already off its surface (e.g. a smooth-surface shadow origin).
Ray shadow_ray_between(const glm::vec3& origin, const glm::vec3& target, const glm::vec3& target_normal);

}  // namespace phyir::render
