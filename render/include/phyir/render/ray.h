#pragma once
#include <glm/glm.hpp>

#include <limits>

namespace phyir::render {

struct Ray {
  glm::vec3 origin{0.0f};
  glm::vec3 direction{0.0f, 0.0f, -1.0f};  // unit length
  float tmin = 0.0f;
  float tmax = std::numeric_limits<float>::infinity();
  // Camera rays: the angle one pixel subtends around this ray (radians; the geometric mean
  // of its two sides), so a hit at distance t sees a footprint about spread x t wide and
  // filters its textures to it. 0 for every other ray: textures at full resolution.
  float spread = 0.0f;
};

// What the accelerator reports; everything else is derived by RenderScene::interact.
struct Hit {
  float t = 0.0f;
  int mesh = -1;       // index into Scene::meshes (the Embree geometry id)
  int triangle = -1;   // index into Mesh::triangles (the Embree primitive id)
  glm::vec2 barycentric{0.0f};  // (b1, b2) of vertices 1 and 2; b0 = 1 - b1 - b2
};

}  // namespace phyir::render
