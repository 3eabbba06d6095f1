#pragma once
// "Simulate only the effects a scene calls for": the renderer inspects the scene before
// rendering and picks an integrator kernel without the code paths for absent effects.
// render.json lists what ran.
#include <nlohmann/json.hpp>

#include "phyir/scenes/scene.h"

namespace phyir::render {

struct Effects {
  bool emitters = false;         // next-event estimation on emissive triangles
  bool punctual_lights = false;  // next-event estimation on KHR_lights_punctual lights
  bool environment = false;   // environment lookups and sampling
  bool transmission = false;  // the dielectric (glass) lobe
  bool textures = false;      // any texture fetch
  bool mirrors = false;       // delta specular lobes (roughness below kMirrorRoughness)
  bool alpha_masking = false;   // alphaMode MASK: hits below the cutoff dropped (Embree filter)
  bool alpha_blending = false;  // alphaMode BLEND: stochastic coverage (Embree filter)

  // Whether next-event estimation runs at all.
  bool light_sampling() const { return emitters || punctual_lights; }

  nlohmann::json to_json() const;
};

// What `scene` (plus an environment, if any) needs.
Effects analyse_effects(const scenes::Scene& scene, bool has_environment);

// Every effect on: the reference the specialised kernels are benchmarked against.
Effects all_effects();

}  // namespace phyir::render
