#pragma once
// Ground-truth labels of one pixel, taken at the first surface seen through the pixel
// centre (an exact, un-averaged label: no depth mixed across object edges, unit normals).
// Conventions (docs/conventions.md):
//   depth    Euclidean distance from the camera centre to the surface, metres (not z-depth)
//   normal   world-space unit shading normal, on the side facing the camera
//   basecolor linear Rec.709 (texture sRGB-decoded, times factor)
//   roughness perceptual R (the BRDF's alpha is R^2), metalness M
// Pixels that see no geometry: every value 0 and `geometry` = 0.
#include <glm/glm.hpp>

#include "phyir/render/interaction.h"

namespace phyir::render {

struct GBufferSample {
  float depth = 0.0f;
  glm::vec3 normal{0.0f};
  glm::vec3 basecolor{0.0f};
  float roughness = 0.0f;
  float metalness = 0.0f;
  float emissive = 0.0f;     // 1 where the surface emits towards the camera
  float transparent = 0.0f;  // 1 where the surface transmits (glass) or is not opaque
  float geometry = 0.0f;     // 1 where the pixel sees a surface

  static GBufferSample from_hit(const SurfaceInteraction& si);
};

}  // namespace phyir::render
