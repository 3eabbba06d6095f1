#pragma once
// A ray's hit turned into everything shading needs: position, normals, UV and the
// material evaluated there (textures applied). Built by RenderScene::interact.
#include <glm/glm.hpp>

#include "phyir/render/brdf.h"

namespace phyir::render {

// Normal convention: BOTH normals point to the side the ray arrived from
// (dot(ray.direction, geometric_normal) <= 0 always). A back-face hit (front_face false)
// has both normals negated relative to the triangle's winding; front_face keeps the
// winding information (emission side, entering vs leaving a transmissive volume).
struct SurfaceInteraction {
  // Barycentric interpolation of the triangle's vertices (on the triangle's plane).
  glm::vec3 position{0.0f};
  // Unit geometric normal: cross(p1 - p0, p2 - p0) normalised (the counter-clockwise
  // front side), negated on back-face hits. Degenerate triangles use the interpolated
  // normal, else the direction back along the ray.
  glm::vec3 geometric_normal{0.0f, 0.0f, 1.0f};
  // Unit shading normal: interpolated vertex normal (the geometric normal if the mesh
  // has none), put on the wound side if the authored normal disagrees, then normal-mapped
  // (a mapped normal below the geometric surface is discarded), negated on back-face hits
  // together with geometric_normal. Same side as geometric_normal.
  glm::vec3 shading_normal{0.0f, 0.0f, 1.0f};
  glm::vec3 tangent{1.0f, 0.0f, 0.0f};  // unit, orthogonal to shading_normal
  // Shadow rays leave from position + shadow_lift: the point lifted onto the smooth surface
  // the vertex normals describe where it bulges above the facet (smooth_surface.h); 0 on
  // flat, concave or flat-shaded geometry.
  glm::vec3 shadow_lift{0.0f};
  bool front_face = true;  // the ray arrived on the side the triangle's winding faces
  glm::vec2 uv{0.0f};       // TEXCOORD_0 (no texture transform), (0,0) when absent
  float distance = 0.0f;   // along the ray
  int mesh = -1;
  int triangle = -1;
  int material = -1;

  // The material at this point (factors times textures).
  BrdfParams brdf;
  // Emitted radiance toward the ray: emissive factor x strength x texture on the front
  // face (both faces if double-sided), 0 on the back of a one-sided emitter.
  glm::vec3 emission{0.0f};
  bool emits = false;          // emission non-zero on the side the ray arrived from
  float transmission = 0.0f;   // KHR_materials_transmission, [0,1]
  float ior = 1.5f;
  float opacity = 1.0f;        // base colour alpha after alphaMode (1 for OPAQUE)
};

}  // namespace phyir::render
