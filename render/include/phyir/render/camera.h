#pragma once
// Cameras turn a continuous pixel position into a world-space ray.
//  - Equirectangular: full 360 x 180 degrees, world-aligned (the camera node's rotation
//    is ignored: panoramas, probes and the network all share the world frame), with the
//    mapping of equirect.h. Only the position matters.
//  - Perspective: the glTF camera's forward/up and vertical field of view; the aspect
//    ratio is the image's.
// Pixel (i, j) covers [i, i+1) x [j, j+1); its centre is (i + 0.5, j + 0.5).
#include <glm/glm.hpp>

#include <string>

#include "phyir/render/ray.h"

namespace phyir::render {

enum class Projection { Equirectangular, Perspective };

struct CameraModel {
  Projection projection = Projection::Equirectangular;
  glm::vec3 position{0.0f};
  glm::vec3 forward{0.0f, 0.0f, -1.0f};  // perspective only
  glm::vec3 up{0.0f, 1.0f, 0.0f};        // perspective only
  float yfov = 1.0f;                      // radians, perspective only
  int width = 512;
  int height = 256;

  // `pixel` in continuous image coordinates ((0,0) = top-left corner).
  Ray generate_ray(const glm::vec2& pixel) const;
  // Inverse: the continuous pixel position a world direction from the camera lands on;
  // false when it is outside the image (perspective only).
  bool project(const glm::vec3& direction, glm::vec2* pixel) const;
};

Projection parse_projection(const std::string& name);  // "equirect" | "perspective"
std::string projection_name(Projection projection);

}  // namespace phyir::render
