#pragma once
// A ray's hit turned into everything shading needs: position, normals, UV and the
// material evaluated there (textures applied). Built by RenderScene::interact.
#include <glm/glm.hpp>

#include "phyir/render/brdf.h"

namespace phyir::render {

struct SurfaceInteraction {
  glm::vec3 position{0.0f};
  // Unit geometric normal of the triangle as wound (counter-clockwise front face).
  glm::vec3 geometric_normal{0.0f, 0.0f, 1.0f};
  // Unit shading normal (interpolated, normal-mapped), flipped to the geometric normal's
  // side when they disagree.
  glm::vec3 shading_normal{0.0f, 0.0f, 1.0f};
  glm::vec3 tangent{1.0f, 0.0f, 0.0f};  // unit, orthogonal to shading_normal
  bool front_face = true;  // the ray arrived on the side geometric_normal points to
  glm::vec2 uv{0.0f};
  float distance = 0.0f;   // along the ray
  int mesh = -1;
  int triangle = -1;
  int material = -1;

  // The material at this point (factors times textures).
  BrdfParams brdf;
  glm::vec3 emission{0.0f};    // emitted radiance (front face, or both faces if double-sided)
  bool emits = false;          // emission non-zero on the side the ray arrived from
  float transmission = 0.0f;   // KHR_materials_transmission, [0,1]
  float ior = 1.5f;
  float opacity = 1.0f;        // base colour alpha after alphaMode (1 for OPAQUE)
};

}  // namespace phyir::render
