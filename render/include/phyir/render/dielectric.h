#pragma once
// Smooth dielectric (glass) from glTF KHR_materials_transmission + KHR_materials_ior:
// a solid refractive interface, as Blender's glTF importer maps it to Cycles, so closed
// meshes behave like glass objects. Reflection with the exact unpolarised Fresnel
// reflectance, refraction with (1 - F) tinted by the base colour. Both lobes are deltas.
// Directions in the local frame of the geometric side wo is on: +z is the side of wo
// when `entering` (outside -> inside), so wo.z > 0 always.
#include <glm/glm.hpp>

namespace phyir::render {

// Exact Fresnel reflectance for unpolarised light; eta = n_transmitted / n_incident.
// Returns 1 under total internal reflection.
float fresnel_dielectric(float cos_theta_i, float eta);

struct DielectricSample {
  glm::vec3 wi{0.0f};
  glm::vec3 weight{0.0f};  // throughput multiplier
  bool transmitted = false;
};

// eta = n_inside / n_outside (the glTF IOR); `entering` says whether wo is outside.
// Radiance is not scaled by 1/eta^2 on crossing: for closed objects the factors of
// entering and leaving cancel, and skipping them keeps throughput bounded.
DielectricSample sample_dielectric(const glm::vec3& wo, float eta, bool entering,
                                   const glm::vec3& tint, float u);

}  // namespace phyir::render
