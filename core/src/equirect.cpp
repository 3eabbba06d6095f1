#include "phyir/core/equirect.h"

#include <cmath>

#include "phyir/core/safe_math.h"

namespace phyir {

glm::vec3 equirect_direction(glm::vec2 uv) {
  const float theta = uv.y * kPi;  // 0 = straight up (+Y)
  return equirect_direction(uv.x, std::cos(theta), std::sin(theta));
}

glm::vec3 equirect_direction(float u, float cos_theta, float sin_theta) {
  const float phi = (u - 0.5f) * kTwoPi;  // 0 at the centre column (-Z), + towards +X
  return glm::vec3(sin_theta * std::sin(phi), cos_theta, -sin_theta * std::cos(phi));
}

glm::vec2 equirect_uv(const glm::vec3& d) {
  float u = 0.5f + std::atan2(d.x, -d.z) * kInvTwoPi;
  if (u >= 1.0f) u -= 1.0f;
  if (u < 0.0f) u += 1.0f;
  const float v = safe_acos(d.y) * kInvPi;
  return glm::vec2(u, v);
}

float equirect_texel_solid_angle(int row, int width, int height) {
  const double theta0 = kPi * double(row) / height;
  const double theta1 = kPi * double(row + 1) / height;
  return static_cast<float>((2.0 * kPi / width) * (std::cos(theta0) - std::cos(theta1)));
}

float equirect_uv_pdf_to_solid_angle(float sin_theta) {
  return sin_theta > 0.0f ? 1.0f / (2.0f * kPi * kPi * sin_theta) : 0.0f;
}

}  // namespace phyir
