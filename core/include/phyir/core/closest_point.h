#pragma once
// The point of a triangle nearest to a point: a lamp's light kept clear of its fitting
// (scenes/lamp_light.h), distances to a scene's surfaces in tests.
#include <glm/glm.hpp>

namespace phyir {

// Ericson, Real-Time Collision Detection 5.1.5: by the Voronoi regions of the corners, the
// edges and the face. A degenerate triangle gives a corner.
glm::vec3 closest_point_on_triangle(const glm::vec3& p, const glm::vec3& a, const glm::vec3& b, const glm::vec3& c);

}  // namespace phyir
