#pragma once
// Emissive triangles whose light can never leave the solid they face: the top of a light
// fixture's diffuser pressed against its housing, a lamp's glowing face inside its shade
// glued shut, emissive faces of modelled-but-hidden parts. Light sampling would spend
// samples on them that every shadow ray then finds blocked; the emitter sampler leaves
// them out instead. That stays unbiased even if the test is wrong: a left-out triangle
// has light-sampling pdf 0, so a BRDF-sampled ray that hits it counts with MIS weight 1.
#include <glm/glm.hpp>

#include "phyir/render/accelerator.h"
#include "phyir/scenes/scene.h"

namespace phyir::render {

// True when every probe ray from the triangle's emitting side(s) (7 points x 5 directions
// per side, the normal and 60 degrees off it) hits the back of a face: the triangle
// emits only into the inside of closed geometry. `normal` is the unit winding normal.
bool emits_only_into_solids(const scenes::Scene& scene, const Accelerator& accelerator, const glm::vec3& p0,
                            const glm::vec3& p1, const glm::vec3& p2, const glm::vec3& normal, bool two_sided);

}  // namespace phyir::render
