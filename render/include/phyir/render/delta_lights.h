#pragma once
// The scene's punctual lights (KHR_lights_punctual: point, spot, directional) as the
// renderer uses them. They are infinitely small (or infinitely far), so no ray ever hits
// one: they are reached by next-event estimation only, without a multiple-importance
// weight, and a camera ray never sees one (probes add each visible one to the texel of its
// direction: render/probes/src/punctual_deposit.h). The EmitterSampler chooses
// between them and the emissive triangles (emitter_sampler.h).
#include <glm/glm.hpp>

#include <vector>

#include "phyir/scenes/scene.h"

namespace phyir::render {

// What a delta light sends to a reference point.
struct DeltaIllumination {
  glm::vec3 wi{0.0f};        // unit, from the reference point towards the light
  float distance = 0.0f;     // to the light; +infinity for a directional light
  glm::vec3 position{0.0f};  // the light (point, spot)
  // Irradiance on a surface facing the light (W/m^2 per channel): I x spot falloff / d^2
  // for points and spots, E for directional lights. The delta in solid angle is implied.
  glm::vec3 irradiance{0.0f};
};

class DeltaLights {
 public:
  // `scene_radius` sizes a directional light's power (the disc of the scene it can light).
  DeltaLights(const std::vector<scenes::PunctualLight>& lights, float scene_radius);

  bool empty() const { return lights_.empty(); }
  int size() const { return static_cast<int>(lights_.size()); }
  int count(scenes::PunctualLight::Type type) const;
  const scenes::PunctualLight& light(int i) const { return lights_[size_t(i)]; }

  // Luminance of the irradiance light `i` gives a surface at `reference` facing it: its
  // selection weight beside the emissive clusters' (same unit), 0 outside a spot's cone.
  float weight(int i, const glm::vec3& reference) const;
  // Emitted power (luminance, W) for power-only selection: 4 pi I for a point, the cone's
  // solid angle (to the middle of its ramp) x I for a spot, E x pi r^2 for a directional.
  float power(int i) const { return power_[size_t(i)]; }
  float total_power() const { return total_power_; }

  // What light `i` sends to `reference`; false when it sends nothing (outside a spot's
  // cone, at the light's own position, a zero light).
  bool illuminate(int i, const glm::vec3& reference, DeltaIllumination* out) const;

  // The distance from `point` to the nearest point or spot light (+infinity without any).
  float distance_bound(const glm::vec3& point) const;

 private:
  std::vector<scenes::PunctualLight> lights_;
  std::vector<glm::vec3> radiometric_;  // W/sr or W/m^2 per channel
  std::vector<float> power_;
  float total_power_ = 0.0f;
};

}  // namespace phyir::render
