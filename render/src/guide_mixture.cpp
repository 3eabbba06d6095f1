#include "phyir/render/guide_mixture.h"

#include "phyir/core/safe_math.h"

namespace phyir::render {

bool sample_guide_mixture(const GuideMixture& mixture, const BrdfParams& brdf, const Frame& frame,
                          const glm::vec3& wo, float u_choice, float u_lobe, const glm::vec2& u, BrdfSample* bs) {
  glm::vec3 wi;
  if (u_choice < mixture.bsdf_fraction) {
    BrdfSample from_brdf;
    if (!brdf_sample(brdf, wo, u_lobe, u, &from_brdf) || from_brdf.delta) return false;
    wi = from_brdf.wi;
  } else {
    wi = frame.to_local(mixture.guide->sample(u));
  }
  if (!(wi.z > 0.0f)) return false;
  const float p = mixture.pdf(brdf_pdf(brdf, wo, wi), frame.to_world(wi));
  const glm::vec3 f = brdf_eval(brdf, wo, wi);
  if (!(p > kTinyDenominator) || !(max_component(f) > 0.0f)) return false;
  bs->wi = wi;
  bs->weight = f * (wi.z / p);
  bs->pdf = p;
  bs->delta = false;
  return true;
}

}  // namespace phyir::render
