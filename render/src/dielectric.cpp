#include "phyir/render/dielectric.h"

#include <algorithm>
#include <cmath>

#include "phyir/core/safe_math.h"

namespace phyir::render {

namespace {

// An IOR that is not a positive finite number means "no interface" (eta = 1: the light
// passes straight through with F = 0) rather than NaN directions.
float sane_eta(float eta) { return (std::isfinite(eta) && eta > 0.0f) ? eta : 1.0f; }

}  // namespace

float fresnel_dielectric(float cos_theta_i, float eta) {
  eta = sane_eta(eta);
  // A cosine on the far side means the roles of the media are swapped (as pbrt's FrDielectric).
  if (cos_theta_i < 0.0f) {
    eta = 1.0f / eta;
    cos_theta_i = -cos_theta_i;
  }
  cos_theta_i = std::min(cos_theta_i, 1.0f);
  // Snell: sin_t = sin_i / eta.
  const float sin2_t = (1.0f - cos_theta_i * cos_theta_i) / (eta * eta);
  if (sin2_t >= 1.0f) return 1.0f;  // total internal reflection
  const float cos_t = safe_sqrt(1.0f - sin2_t);
  // Fresnel amplitudes for p- and s-polarised light; unpolarised F is their mean square.
  const float r_parl = (eta * cos_theta_i - cos_t) / (eta * cos_theta_i + cos_t);
  const float r_perp = (cos_theta_i - eta * cos_t) / (cos_theta_i + eta * cos_t);
  return clamp01(0.5f * (r_parl * r_parl + r_perp * r_perp));
}

DielectricSample sample_dielectric(const glm::vec3& wo, float eta, bool entering,
                                   const glm::vec3& tint, float u) {
  DielectricSample s;
  eta = sane_eta(eta);
  // Relative IOR across the interface as seen from wo: n_transmitted / n_incident.
  const float eta_rel = entering ? eta : 1.0f / eta;
  const float cos_i = clamp01(wo.z);  // wo.z > 0 by contract; clamp rounding
  const float F = fresnel_dielectric(cos_i, eta_rel);

  if (u < F) {
    // Specular reflection, chosen with probability F: weight F / F = 1.
    s.wi = glm::vec3(-wo.x, -wo.y, wo.z);
    s.weight = glm::vec3(1.0f);
    s.transmitted = false;
    return s;
  }
  // Refraction, chosen with probability 1 - F (> 0 here, so no TIR): weight
  // (1 - F) tint / (1 - F) = tint. No 1/eta^2 radiance scaling (see dielectric.h).
  // Snell in vector form: wi = -wo / eta + (cos_i / eta - cos_t) n.
  const float sin2_t = (1.0f - cos_i * cos_i) / (eta_rel * eta_rel);
  const float cos_t = safe_sqrt(1.0f - sin2_t);
  s.wi = safe_normalize(glm::vec3(-wo.x / eta_rel, -wo.y / eta_rel, -cos_t),
                        glm::vec3(0.0f, 0.0f, -1.0f));
  s.weight = tint;
  s.transmitted = true;
  return s;
}

}  // namespace phyir::render
