#pragma once
// Where a lamp's point light goes. Sweet Home 3D renders a light source as a glowing sphere
// of its diameter; a point light gives the same light as that sphere only outside it. A
// catalog source whose sphere cuts the lamp's own surfaces would light them from almost zero
// distance, a hot spot of ~1/distance^2 that neither the sphere nor a real bulb makes, so
// the light moves straight away from the nearest surface until the sphere clears it (docs/apartments.md, "Light").
#include <glm/glm.hpp>

#include <vector>

#include "phyir/scenes/asset_model.h"

namespace phyir::scenes {

// `at` moved, in at most a few steps, to at least `radius` from every triangle of `meshes`
// (same frame); unchanged when it already is.
glm::vec3 clear_of_surfaces(const std::vector<const AssetMesh*>& meshes, glm::vec3 at, float radius);

}  // namespace phyir::scenes
