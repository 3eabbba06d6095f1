#include "phyir/render/camera.h"

#include <algorithm>
#include <cmath>

#include "phyir/core/error.h"
#include "phyir/core/safe_math.h"
#include "phyir/render/equirect.h"

namespace phyir::render {

namespace {

struct PerspectiveBasis {
  glm::vec3 right, up, forward;
  float tan_half_y, tan_half_x;
};

PerspectiveBasis perspective_basis(const CameraModel& c) {
  PerspectiveBasis b;
  b.forward = safe_normalize(c.forward, glm::vec3(0, 0, -1));
  b.right = safe_normalize(glm::cross(b.forward, c.up), glm::vec3(1, 0, 0));
  b.up = glm::cross(b.right, b.forward);
  b.tan_half_y = std::tan(0.5f * c.yfov);
  b.tan_half_x = b.tan_half_y * float(c.width) / float(c.height);
  return b;
}

}  // namespace

Ray CameraModel::generate_ray(const glm::vec2& pixel) const {
  Ray ray;
  ray.origin = position;
  if (projection == Projection::Equirectangular) {
    ray.direction = equirect_direction(glm::vec2(pixel.x / width, pixel.y / height));
    // A pixel spans pi / height in latitude and 2 pi / width x sin(polar angle) in longitude.
    const float sin_polar = std::sqrt(std::max(0.0f, 1.0f - ray.direction.y * ray.direction.y));
    ray.spread = std::sqrt(kPi / float(height) * kTwoPi / float(width) * sin_polar);
    return ray;
  }
  const PerspectiveBasis b = perspective_basis(*this);
  const float sx = (2.0f * pixel.x / width - 1.0f) * b.tan_half_x;
  const float sy = (1.0f - 2.0f * pixel.y / height) * b.tan_half_y;
  ray.direction = safe_normalize(b.forward + sx * b.right + sy * b.up, b.forward);
  // A pixel of the image plane at distance 1, seen off-axis: its sides shrink by cos and cos^2.
  const float cos_axis = std::max(glm::dot(ray.direction, b.forward), 0.0f);
  ray.spread = std::sqrt(2.0f * b.tan_half_x / float(width) * 2.0f * b.tan_half_y / float(height)) *
               std::pow(cos_axis, 1.5f);
  return ray;
}

bool CameraModel::project(const glm::vec3& direction, glm::vec2* pixel) const {
  if (projection == Projection::Equirectangular) {
    const glm::vec2 uv = equirect_uv(direction);
    *pixel = glm::vec2(uv.x * width, uv.y * height);
    return true;
  }
  const PerspectiveBasis b = perspective_basis(*this);
  const float z = glm::dot(direction, b.forward);
  if (z <= 0.0f) return false;
  const float sx = glm::dot(direction, b.right) / z / b.tan_half_x;
  const float sy = glm::dot(direction, b.up) / z / b.tan_half_y;
  *pixel = glm::vec2((sx + 1.0f) * 0.5f * width, (1.0f - sy) * 0.5f * height);
  return pixel->x >= 0 && pixel->x <= width && pixel->y >= 0 && pixel->y <= height;
}

Projection parse_projection(const std::string& name) {
  if (name == "equirect" || name == "equirectangular") return Projection::Equirectangular;
  if (name == "perspective") return Projection::Perspective;
  fail("unknown projection '{}': use equirect or perspective", name);
}

std::string projection_name(Projection projection) {
  return projection == Projection::Equirectangular ? "equirect" : "perspective";
}

}  // namespace phyir::render
