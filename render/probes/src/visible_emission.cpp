#include "visible_emission.h"

#include <algorithm>
#include <cmath>

#include "phyir/core/safe_math.h"
#include "phyir/render/equirect.h"
#include "phyir/render/probe_grid.h"

namespace phyir::render {

glm::vec3 visible_emission(const EmitterCoverage::View& lights, const std::vector<EmitterCoverage::View::Piece>& pieces,
                           const Accelerator& accelerator, const glm::vec3& origin, int count, Rng& rng,
                           const FootIrradiance& foot, glm::vec3* emission_cos, std::vector<glm::vec2>* strata,
                           uint64_t* rays) {
  // A part's box is tight, so most points fall inside; a sliver may need a few rounds.
  constexpr int kMaxRounds = 4;
  // Occlusion rays stop this fraction short of the light's plane, so the light hides nothing.
  constexpr float kShortOfTheLight = 1e-4f;
  double covered = 0.0;
  for (const auto& piece : pieces) covered += piece.fraction;
  glm::dvec3 sum(0.0), sum_cos(0.0);
  for (const auto& piece : pieces) {
    const int wanted = std::max(1, int(std::lround(count * piece.fraction / covered)));
    int inside = 0, visible = 0;
    double visible_cos = 0.0;
    glm::vec3 last(0.0f);
    for (int round = 0; round < kMaxRounds && 2 * inside < wanted; ++round) {
      stratified_square(wanted, rng, strata);
      for (const glm::vec2& a : *strata) {
        const double phi = piece.lo.x + double(a.x) * (piece.hi.x - piece.lo.x);
        const double z = std::clamp(piece.lo.y + double(a.y) * (piece.hi.y - piece.lo.y), -1.0, 1.0);
        const glm::vec3 d = equirect_direction(float(phi / kTwoPi + 0.5), float(z), float(std::sqrt(1.0 - z * z)));
        float distance = 0.0f;
        if (!lights.hits(piece.light, d, &distance)) continue;
        ++inside;
        ++*rays;
        last = d;
        if (accelerator.occluded(Ray{origin, d, 0.0f, distance * (1.0f - kShortOfTheLight)})) continue;
        ++visible;
        visible_cos += foot.cosine(d);
      }
    }
    // A sliver no point found is taken as in view (its share of the texel is negligible).
    const double seen = inside > 0 ? double(visible) / inside : 1.0;
    const double seen_cos = inside > 0 ? visible_cos / inside : foot.cosine(last);
    sum += glm::dvec3(piece.emission) * (piece.fraction * seen);
    sum_cos += glm::dvec3(piece.emission) * (piece.fraction * seen_cos);
  }
  *emission_cos = glm::vec3(sum_cos);
  return glm::vec3(sum);
}

}  // namespace phyir::render
