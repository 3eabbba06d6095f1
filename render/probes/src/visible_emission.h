#pragma once
// Emission a texel sees inside the lights' exact coverage (emitter_coverage.h). Internal.
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "emitter_coverage.h"
#include "foot_correction.h"
#include "phyir/render/accelerator.h"
#include "phyir/render/rng.h"

namespace phyir::render {

// The emission a texel sees: `count` directions split between the lights' parts of it
// (`pieces`) by size, stratified in each part's (phi, cos theta) box and kept inside its
// triangle, each only asking whether something hides the light. *emission_cos: the same times
// the cosine to the probe's normal (FootIrradiance); `strata`: scratch; rays counted in *rays.
glm::vec3 visible_emission(const EmitterCoverage::View& lights, const std::vector<EmitterCoverage::View::Piece>& pieces,
                           const Accelerator& accelerator, const glm::vec3& origin, int count, Rng& rng,
                           const FootIrradiance& foot, glm::vec3* emission_cos, std::vector<glm::vec2>* strata,
                           uint64_t* rays);

}  // namespace phyir::render
