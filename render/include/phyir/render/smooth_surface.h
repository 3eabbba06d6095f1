#pragma once
// Where a shadow ray leaves a smooth-shaded triangle from (Hanika 2021, "Hacking the Shadow
// Terminator", Ray Tracing Gems II, ch. 4; Cycles' "shadow terminator geometry offset"): a
// coarse mesh with interpolated normals stands for a smooth surface that bulges above its
// flat facets where it is convex. Shading with the interpolated normal while testing
// visibility from the facet darkens a band before the shading terminator (the light is above
// the normal's horizon but below the facet's plane, and the ray hits the mesh itself); from
// the point on the implied smooth surface the ray clears it, as on the smooth surface.
#include <glm/glm.hpp>

#include "phyir/scenes/scene.h"

namespace phyir::render {

// The point p (on triangle `tri` at barycentrics `bary`) moved onto the smooth surface its
// vertex normals describe: each vertex's tangent plane lifts p when p lies below it, the
// lifts are blended by the barycentrics. Only ever moves p to the `side` (the geometric
// normal on the side being shaded): where the mesh is flat or concave, p itself. The lift is
// at most the triangle's longest edge; without (finite) vertex normals, p.
glm::vec3 smooth_surface_point(const scenes::Mesh& mesh, const glm::uvec3& tri, const glm::vec3& bary,
                               const glm::vec3& p, const glm::vec3& side);

}  // namespace phyir::render
