#pragma once
// The emission a probe texel sees directly, where the lights' exact coverage of the texel is
// known (emitter_coverage.h). Internal to the probe renderer.
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "emitter_coverage.h"
#include "foot_correction.h"
#include "phyir/render/accelerator.h"
#include "phyir/render/rng.h"

namespace phyir::render {

// The emission a light texel sees, sampled only where the lights cover it. Each light
// triangle's part of the texel is known exactly (EmitterCoverage); `count` directions, split
// between the parts by their size, are drawn uniformly in solid angle inside them (stratified
// points of a part's bounding box in the equal-area (phi, cos theta) map, kept where they fall
// inside the triangle: the others cost no ray), and each asks only whether something hides
// the light. Where a light is in full view the estimate is exact; elsewhere every direction
// lands on the light, where an occluder's edge cuts it, none on the rest of the texel.
// *emission_cos receives the same times the cosine to the probe's normal (FootIrradiance).
glm::vec3 visible_emission(const EmitterCoverage::View& lights, const std::vector<EmitterCoverage::View::Piece>& pieces,
                           const Accelerator& accelerator, const glm::vec3& origin, int count, Rng& rng,
                           const FootIrradiance& foot, glm::vec3* emission_cos, std::vector<glm::vec2>* strata,
                           uint64_t* rays);

}  // namespace phyir::render
