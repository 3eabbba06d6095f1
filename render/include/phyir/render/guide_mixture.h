#pragma once
// Path guiding's sampling at one vertex (docs/guiding.md): one-sample MIS between the BRDF
// and a learned directional distribution (render/guiding), the direction drawn from the
// BRDF with probability a (bsdf_fraction) and from the guide otherwise, and weighted by the
// mixture's density p = a p_brdf + (1 - a) p_guide whichever drew it. Because a > 0, every
// direction the BRDF can reach keeps p > 0: the guide changes the variance, never the mean.
// Next-event estimation weighs its light samples against this p (direct_lighting.h).
#include <glm/glm.hpp>

#include "phyir/render/brdf.h"
#include "phyir/render/frame.h"
#include "phyir/render/guiding/directional_quadtree.h"

namespace phyir::render {

struct GuideMixture {
  const guiding::DirectionalQuadtree* guide = nullptr;  // null: the BRDF alone
  float bsdf_fraction = 1.0f;                           // a, in (0, 1]

  bool active() const { return guide != nullptr; }
  // The density of wi_world under the mixture, given the BRDF's density of it (exactly
  // brdf_pdf when inactive, so unguided estimates keep their bits).
  float pdf(float brdf_pdf, const glm::vec3& wi_world) const {
    if (!guide) return brdf_pdf;
    return bsdf_fraction * brdf_pdf + (1.0f - bsdf_fraction) * guide->pdf(wi_world);
  }
};

// A direction from the mixture at a non-mirror shading point (frame, wo local; the guide is
// in world space): from the BRDF (u_lobe, u) when u_choice < a, else from the guide (u).
// bs: wi local, weight f cos / p, pdf p (the mixture's), never delta. False when the
// direction carries nothing (below the surface, or of density 0).
bool sample_guide_mixture(const GuideMixture& mixture, const BrdfParams& brdf, const Frame& frame,
                          const glm::vec3& wo, float u_choice, float u_lobe, const glm::vec2& u, BrdfSample* bs);

}  // namespace phyir::render
