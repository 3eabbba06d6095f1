#include "phyir/render/delta_lights.h"

#include <cmath>
#include <limits>

#include "phyir/core/safe_math.h"

namespace phyir::render {

using Type = scenes::PunctualLight::Type;

DeltaLights::DeltaLights(const std::vector<scenes::PunctualLight>& lights, float scene_radius) : lights_(lights) {
  for (const scenes::PunctualLight& light : lights_) {
    const glm::vec3 value = light.radiometric();
    radiometric_.push_back(value);
    float solid_angle = 4.0f * kPi;
    if (light.type == Type::Spot)
      solid_angle = 2.0f * kPi * (1.0f - std::cos(0.5f * (light.inner_cone_angle + light.outer_cone_angle)));
    const float power = light.type == Type::Directional ? luminance(value) * kPi * scene_radius * scene_radius
                                                        : luminance(value) * solid_angle;
    power_.push_back(std::isfinite(power) && power > 0.0f ? power : 0.0f);
    total_power_ += power_.back();
  }
}

int DeltaLights::count(Type type) const {
  int n = 0;
  for (const scenes::PunctualLight& light : lights_) n += light.type == type ? 1 : 0;
  return n;
}

bool DeltaLights::illuminate(int i, const glm::vec3& reference, DeltaIllumination* out) const {
  const scenes::PunctualLight& light = lights_[size_t(i)];
  if (light.type == Type::Directional) {
    out->wi = -light.direction;
    out->distance = std::numeric_limits<float>::infinity();
    out->position = reference;
    out->irradiance = radiometric_[size_t(i)];
    return max_component(out->irradiance) > 0.0f;
  }
  const glm::vec3 d = light.position - reference;
  const float dist2 = glm::dot(d, d);
  // At the light itself the irradiance is unbounded: nothing sensible to add.
  if (!(dist2 > 0.0f) || !std::isfinite(dist2)) return false;
  out->distance = std::sqrt(dist2);
  out->wi = d / out->distance;
  out->position = light.position;
  const float falloff = light.type == Type::Spot ? light.spot_falloff(glm::dot(light.direction, -out->wi)) : 1.0f;
  out->irradiance = radiometric_[size_t(i)] * (falloff / dist2);
  return falloff > 0.0f && is_finite(out->irradiance) && max_component(out->irradiance) > 0.0f;
}

float DeltaLights::weight(int i, const glm::vec3& reference) const {
  DeltaIllumination seen;
  return illuminate(i, reference, &seen) ? luminance(seen.irradiance) : 0.0f;
}

float DeltaLights::distance_bound(const glm::vec3& point) const {
  float nearest = std::numeric_limits<float>::infinity();
  for (const scenes::PunctualLight& light : lights_)
    if (light.type != Type::Directional) nearest = std::min(nearest, glm::length(light.position - point));
  return nearest;
}

}  // namespace phyir::render
