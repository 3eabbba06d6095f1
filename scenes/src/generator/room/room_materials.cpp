// The material palette: what each role looks like, with seeded variation. Colours are
// linear Rec.709; texture colours are sRGB-encoded because they become PNG texels.
#include "generator/room/room_materials.h"

#include <algorithm>

namespace phyir::scenes {

namespace {

using glm::vec3;

// Emission colours, normalised so the largest channel is 1 (glTF keeps emissiveFactor in
// [0,1]; KHR_materials_emissive_strength carries the magnitude).
const std::vector<vec3> kLightColours = {
    {1.0f, 0.84f, 0.64f},  // warm white, about 3000 K
    {1.0f, 0.93f, 0.85f},  // neutral white, about 4000 K
    {0.90f, 0.95f, 1.0f},  // cool white, about 6500 K
};

const std::vector<vec3> kWallColours = {
    {0.80f, 0.78f, 0.72f}, {0.66f, 0.57f, 0.45f}, {0.56f, 0.57f, 0.58f},
    {0.45f, 0.54f, 0.63f}, {0.46f, 0.52f, 0.40f}, {0.75f, 0.70f, 0.66f},
};
const std::vector<vec3> kAccentColours = {
    {0.50f, 0.20f, 0.12f}, {0.08f, 0.14f, 0.32f}, {0.12f, 0.25f, 0.16f}, {0.30f, 0.30f, 0.30f},
};
const std::vector<vec3> kPaintColours = {
    {0.70f, 0.70f, 0.68f}, {0.10f, 0.10f, 0.11f}, {0.55f, 0.35f, 0.18f}, {0.20f, 0.32f, 0.45f},
};
const std::vector<vec3> kLacquerColours = {
    {0.60f, 0.05f, 0.04f}, {0.02f, 0.10f, 0.35f}, {0.90f, 0.75f, 0.10f}, {0.03f, 0.03f, 0.03f},
};
// Measured F0 of metals (linear sRGB), as tabulated for the UE4/Filament metalness model.
const std::vector<vec3> kMetalColours = {
    {0.56f, 0.57f, 0.58f},  // iron / steel
    {0.91f, 0.92f, 0.92f},  // aluminium
    {0.95f, 0.64f, 0.54f},  // copper
    {1.00f, 0.71f, 0.29f},  // gold
    {0.55f, 0.56f, 0.55f},  // chromium
};
// Wood texture colours (sRGB-encoded): light grain / dark grain.
const std::vector<std::pair<vec3, vec3>> kWoodTones = {
    {{0.78f, 0.60f, 0.40f}, {0.58f, 0.40f, 0.24f}},  // oak
    {{0.52f, 0.33f, 0.20f}, {0.32f, 0.19f, 0.11f}},  // walnut
    {{0.86f, 0.74f, 0.56f}, {0.70f, 0.56f, 0.38f}},  // birch
};

vec3 jitter(Pcg32& rng, vec3 colour) {
  return glm::clamp(colour * rng.uniform(0.9f, 1.05f), vec3(0.0f), vec3(1.0f));
}

MaterialSpec dielectric(MaterialKind kind, vec3 colour, float roughness) {
  MaterialSpec m;
  m.kind = kind;
  m.base_color = colour;
  m.metallic = 0.0f;
  m.roughness = roughness;
  return m;
}

MaterialSpec metal(MaterialKind kind, vec3 colour, float roughness) {
  MaterialSpec m = dielectric(kind, colour, roughness);
  m.metallic = 1.0f;
  return m;
}

MaterialSpec emitter(vec3 colour, float strength) {
  // The emitter's surface is a white diffuser; glTF adds emission on top of reflection.
  MaterialSpec m = dielectric(MaterialKind::Emissive, vec3(0.8f), 1.0f);
  m.emissive_factor = colour;
  m.emissive_strength = strength;
  return m;
}

// What make() returns for a role no step knows (none: every role has its step).
MaterialSpec fallback_material() { return dielectric(MaterialKind::Diffuse, vec3(0.8f), 1.0f); }

const char* role_name(MaterialRole role) {
  switch (role) {
    case MaterialRole::Wall: return "wall";
    case MaterialRole::AccentWall: return "accent_wall";
    case MaterialRole::Floor: return "floor";
    case MaterialRole::Ceiling: return "ceiling";
    case MaterialRole::Wood: return "wood";
    case MaterialRole::Paint: return "paint";
    case MaterialRole::Fabric: return "fabric";
    case MaterialRole::Lacquer: return "lacquer";
    case MaterialRole::Ceramic: return "ceramic";
    case MaterialRole::RoughMetal: return "rough_metal";
    case MaterialRole::PolishedMetal: return "polished_metal";
    case MaterialRole::WornMetal: return "worn_metal";
    case MaterialRole::Mirror: return "mirror";
    case MaterialRole::Glass: return "glass";
    case MaterialRole::Checker: return "checker";
    case MaterialRole::LightPanel: return "light_panel";
    case MaterialRole::LampShade: return "lamp_shade";
    case MaterialRole::BrightBulb: return "bright_bulb";
  }
  return "material";
}

}  // namespace

MaterialPalette::MaterialPalette(Pcg32 rng, RoomPreset preset, uint64_t texture_seed,
                                 std::vector<MaterialSpec>& materials,
                                 std::vector<TextureSpec>& textures)
    : rng_(rng), preset_(preset), texture_seed_(texture_seed),
      materials_(materials), textures_(textures) {}

int MaterialPalette::get(MaterialRole role) {
  const auto found = by_role_.find(role);
  if (found != by_role_.end()) return found->second;
  MaterialSpec spec = preset_ == RoomPreset::Diffuse ? make_diffuse(role) : make(role);
  spec.name = role_name(role);
  materials_.push_back(spec);
  const int index = static_cast<int>(materials_.size()) - 1;
  by_role_[role] = index;
  return index;
}

int MaterialPalette::add_texture(const std::string& name, TexturePattern pattern, int size,
                                 vec3 a, vec3 b) {
  TextureSpec t;
  t.name = name;
  t.pattern = pattern;
  t.size = size;
  t.colour_a = a;
  t.colour_b = b;
  t.seed = mix64(texture_seed_ + textures_.size());
  textures_.push_back(t);
  return static_cast<int>(textures_.size()) - 1;
}

// The diffuse preset: lights as usual, everything else rough, non-metallic, untextured.
MaterialSpec MaterialPalette::make_diffuse(MaterialRole role) {
  switch (role) {
    case MaterialRole::LightPanel:
    case MaterialRole::LampShade:
    case MaterialRole::BrightBulb:
      return make(role);
    case MaterialRole::Wall:
    case MaterialRole::Ceiling:
      return dielectric(MaterialKind::Diffuse, jitter(rng_, rng_.pick(kWallColours)), 1.0f);
    case MaterialRole::Floor:
      return dielectric(MaterialKind::Diffuse, jitter(rng_, vec3(0.25f, 0.24f, 0.22f)), 1.0f);
    default:
      return dielectric(MaterialKind::Diffuse, jitter(rng_, rng_.pick(kPaintColours)), 1.0f);
  }
}

// Every random draw is its own statement: the evaluation order of function arguments is
// unspecified, and two draws in one call could differ between compilers. Each role draws only
// in its own step, so the steps below draw exactly as one switch over every role would.
MaterialSpec MaterialPalette::make(MaterialRole role) {
  switch (role) {
    case MaterialRole::Wall:
    case MaterialRole::AccentWall:
    case MaterialRole::Ceiling:
      return make_shell(role);
    case MaterialRole::Floor:
      return make_floor();
    case MaterialRole::Wood:
    case MaterialRole::Paint:
    case MaterialRole::Fabric:
    case MaterialRole::Lacquer:
    case MaterialRole::Ceramic:
    case MaterialRole::Checker:
      return make_furniture(role);
    case MaterialRole::RoughMetal:
    case MaterialRole::PolishedMetal:
    case MaterialRole::WornMetal:
    case MaterialRole::Mirror:
    case MaterialRole::Glass:
      return make_specular(role);
    case MaterialRole::LightPanel:
    case MaterialRole::LampShade:
    case MaterialRole::BrightBulb:
      return make_light(role);
  }
  return fallback_material();
}

// Walls, the accent wall and the ceiling: diffuse paint.
MaterialSpec MaterialPalette::make_shell(MaterialRole role) {
  switch (role) {
    case MaterialRole::Wall: {
      const vec3 colour = jitter(rng_, rng_.pick(kWallColours));
      return dielectric(MaterialKind::Diffuse, colour, rng_.uniform(0.8f, 1.0f));
    }
    case MaterialRole::AccentWall: {
      const vec3 colour = jitter(rng_, rng_.pick(kAccentColours));
      return dielectric(MaterialKind::Diffuse, colour, rng_.uniform(0.7f, 0.95f));
    }
    case MaterialRole::Ceiling:
      return dielectric(MaterialKind::Diffuse, vec3(rng_.uniform(0.78f, 0.86f)), 0.95f);
    default:
      return fallback_material();
  }
}

// mini: a textured wood floor half of the time; hard: always wood planks or tiles.
MaterialSpec MaterialPalette::make_floor() {
  const bool hard = preset_ == RoomPreset::Hard;
  const bool textured = hard || rng_.chance(0.5f);
  if (!textured) {
    return dielectric(MaterialKind::Diffuse, jitter(rng_, vec3(0.25f, 0.24f, 0.22f)), 0.95f);
  }
  if (hard && rng_.chance(0.4f)) {
    // Glazed tiles: 4 x 4 tiles of 0.3 m per texture.
    const float roughness = rng_.uniform(0.12f, 0.25f);
    const vec3 glaze = jitter(rng_, vec3(0.85f, 0.84f, 0.80f));
    MaterialSpec m = dielectric(MaterialKind::Glossy, vec3(1.0f), roughness);
    m.base_color_texture = add_texture("tiles", TexturePattern::Tiles, 512, glaze, vec3(0.45f));
    m.texture_repeats_per_metre = 1.0f / 1.2f;
    return m;
  }
  const auto& tone = rng_.pick(kWoodTones);
  MaterialSpec m = dielectric(MaterialKind::Diffuse, vec3(1.0f), rng_.uniform(0.45f, 0.7f));
  m.base_color_texture =
      add_texture("floor_wood", TexturePattern::WoodPlanks, hard ? 512 : 256, tone.first, tone.second);
  m.texture_repeats_per_metre = 0.5f;  // the texture holds 2 m of planks
  return m;
}

// Furniture finishes: wood, paint, fabric, lacquer, ceramic and the checker pattern.
MaterialSpec MaterialPalette::make_furniture(MaterialRole role) {
  switch (role) {
    case MaterialRole::Wood: {
      const bool hard = preset_ == RoomPreset::Hard;
      if (!hard) return dielectric(MaterialKind::Diffuse, vec3(0.35f, 0.20f, 0.10f), 0.7f);
      const auto& tone = rng_.pick(kWoodTones);
      MaterialSpec m = dielectric(MaterialKind::Diffuse, vec3(1.0f), rng_.uniform(0.5f, 0.75f));
      m.base_color_texture = add_texture("wood", TexturePattern::WoodPlanks, 256, tone.first, tone.second);
      m.texture_repeats_per_metre = 1.0f;
      return m;
    }
    case MaterialRole::Paint: {
      const vec3 colour = jitter(rng_, rng_.pick(kPaintColours));
      return dielectric(MaterialKind::Diffuse, colour, rng_.uniform(0.6f, 0.85f));
    }
    case MaterialRole::Fabric:
      return dielectric(MaterialKind::Diffuse, jitter(rng_, rng_.pick(kAccentColours)), 1.0f);
    case MaterialRole::Lacquer: {
      const vec3 colour = jitter(rng_, rng_.pick(kLacquerColours));
      return dielectric(MaterialKind::Glossy, colour, rng_.uniform(0.04f, 0.15f));
    }
    case MaterialRole::Ceramic: {
      const vec3 colour(rng_.uniform(0.75f, 0.85f));
      return dielectric(MaterialKind::Glossy, colour, rng_.uniform(0.08f, 0.2f));
    }
    case MaterialRole::Checker: {
      const vec3 light = jitter(rng_, vec3(0.85f));
      const vec3 dark = jitter(rng_, rng_.pick(kAccentColours));
      MaterialSpec m = dielectric(MaterialKind::Diffuse, vec3(1.0f), 0.8f);
      m.base_color_texture = add_texture("checker", TexturePattern::Checker, 256, light, dark);
      m.texture_repeats_per_metre = 2.5f;  // 8 x 8 squares of 5 cm
      return m;
    }
    default:
      return fallback_material();
  }
}

// Metals, the mirror and glass: the specular materials.
MaterialSpec MaterialPalette::make_specular(MaterialRole role) {
  switch (role) {
    case MaterialRole::RoughMetal: {
      const vec3 f0 = rng_.pick(kMetalColours);
      return metal(MaterialKind::RoughMetal, f0, rng_.uniform(0.4f, 0.65f));
    }
    case MaterialRole::PolishedMetal: {
      const vec3 f0 = rng_.pick(kMetalColours);
      return metal(MaterialKind::PolishedMetal, f0, rng_.uniform(0.03f, 0.12f));
    }
    case MaterialRole::WornMetal: {
      // Factors of 1 pass the texture through: G = roughness, B = metalness.
      MaterialSpec m = metal(MaterialKind::RoughMetal, rng_.pick(kMetalColours), 1.0f);
      m.metallic_roughness_texture =
          add_texture("worn_metal_mr", TexturePattern::WornMetal, 256, vec3(0.0f), vec3(0.0f));
      m.texture_repeats_per_metre = 1.0f;
      return m;
    }
    case MaterialRole::Mirror:
      // Silver-backed glass reflects about 95%; roughness 0 is the perfect-mirror branch.
      return metal(MaterialKind::Mirror, vec3(0.96f, 0.95f, 0.92f), 0.0f);
    case MaterialRole::Glass: {
      MaterialSpec m = dielectric(MaterialKind::Glass, vec3(1.0f), 0.0f);
      m.transmission = 1.0f;
      m.ior = 1.5f;  // soda-lime glass
      return m;
    }
    default:
      return fallback_material();
  }
}

// Radiances in W / (sr m^2) = emissive_factor * emissive_strength (docs/commands/scenes-generate.md).
MaterialSpec MaterialPalette::make_light(MaterialRole role) {
  switch (role) {
    case MaterialRole::LightPanel: {
      const vec3 colour = rng_.pick(kLightColours);
      const bool hard = preset_ == RoomPreset::Hard;
      return emitter(colour, hard ? rng_.uniform(12.0f, 40.0f) : rng_.uniform(18.0f, 30.0f));
    }
    case MaterialRole::LampShade: {
      const vec3 colour = rng_.pick(kLightColours);
      return emitter(colour, rng_.uniform(8.0f, 20.0f));
    }
    case MaterialRole::BrightBulb: {
      // A 5 cm sphere at 300-600 W/(sr m^2) emits as much as a ceiling panel from 1/100 of
      // its area: a small, hard-to-sample light.
      const vec3 colour = rng_.pick(kLightColours);
      return emitter(colour, rng_.uniform(300.0f, 600.0f));
    }
    default:
      return fallback_material();
  }
}

}  // namespace phyir::scenes
