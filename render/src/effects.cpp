#include "phyir/render/effects.h"

#include "phyir/render/brdf.h"

namespace phyir::render {

nlohmann::json Effects::to_json() const {
  return {{"emitter_sampling", emitters}, {"punctual_lights", punctual_lights}, {"environment", environment},
          {"transmission", transmission}, {"textures", textures},
          {"mirrors", mirrors},           {"alpha_masking", alpha_masking},
          {"alpha_blending", alpha_blending}};
}

Effects analyse_effects(const scenes::Scene& scene, bool has_environment) {
  std::vector<bool> used(scene.materials.size(), false);
  for (const scenes::Mesh& mesh : scene.meshes)
    if (!mesh.triangles.empty() && mesh.material >= 0 && size_t(mesh.material) < used.size())
      used[mesh.material] = true;
  Effects e;
  e.environment = has_environment;
  e.punctual_lights = !scene.lights.empty();
  for (size_t i = 0; i < scene.materials.size(); ++i) {
    if (!used[i]) continue;
    const scenes::Material& m = scene.materials[i];
    e.emitters |= m.is_emissive();
    e.transmission |= m.is_transmissive();
    e.textures |= m.is_textured();
    // A metallic-roughness texture can reach roughness 0 anywhere its factor allows.
    e.mirrors |= is_mirror(m.roughness_factor) ||
                 (m.metallic_roughness_texture.present() && m.roughness_factor > 0.0f);
    e.alpha_masking |= m.alpha_mode == scenes::AlphaMode::Mask;
    e.alpha_blending |= m.alpha_mode == scenes::AlphaMode::Blend;
  }
  return e;
}

Effects all_effects() {
  Effects e;
  e.emitters = e.punctual_lights = e.environment = e.transmission = e.textures = e.mirrors = e.alpha_masking = e.alpha_blending = true;
  return e;
}

}  // namespace phyir::render
