#pragma once
#include <glm/glm.hpp>

#include <limits>

namespace phyir::render {

struct Ray {
  glm::vec3 origin{0.0f};
  glm::vec3 direction{0.0f, 0.0f, -1.0f};  // unit length
  float tmin = 0.0f;
  float tmax = std::numeric_limits<float>::infinity();
  // The pixel's cone, for texture filtering: a hit at distance t sees a footprint about
  // width + spread x t wide and filters its textures to it. Camera rays: width 0 and the
  // angle one pixel subtends (radians; the geometric mean of its two sides). The path's
  // later rays keep the angle and start as wide as the footprint they leave (path_tracer.cpp).
  // 0 and 0 (probe texels, light and shadow rays): textures at full resolution.
  float spread = 0.0f;
  float width = 0.0f;  // metres, at the origin
};

// What the accelerator reports; everything else is derived by RenderScene::interact.
struct Hit {
  float t = 0.0f;
  int mesh = -1;       // index into Scene::meshes (the Embree geometry id)
  int triangle = -1;   // index into Mesh::triangles (the Embree primitive id)
  glm::vec2 barycentric{0.0f};  // (b1, b2) of vertices 1 and 2; b0 = 1 - b1 - b2
};

}  // namespace phyir::render
