// plan_room(): what goes into a mini or a hard room, in which order.
#include <string>

#include "generator/room/room_furniture.h"
#include "generator/room/room_materials.h"
#include "generator/room/room_placement.h"
#include "generator/room/room_plan_steps.h"
#include "phyir/core/error.h"
#include "phyir/scenes/room_layout.h"

namespace phyir::scenes {

RoomPreset parse_room_preset(const std::string& name) {
  if (name == "mini") return RoomPreset::Mini;
  if (name == "hard") return RoomPreset::Hard;
  if (name == "diffuse") return RoomPreset::Diffuse;
  fail("unknown room preset '{}' (expected 'mini', 'hard' or 'diffuse')", name);
}

const char* room_preset_name(RoomPreset preset) {
  switch (preset) {
    case RoomPreset::Hard: return "hard";
    case RoomPreset::Diffuse: return "diffuse";
    case RoomPreset::Mini: break;
  }
  return "mini";
}

const char* material_kind_name(MaterialKind kind) {
  switch (kind) {
    case MaterialKind::Diffuse: return "diffuse";
    case MaterialKind::Glossy: return "glossy";
    case MaterialKind::RoughMetal: return "metal_rough";
    case MaterialKind::PolishedMetal: return "metal_polished";
    case MaterialKind::Mirror: return "mirror";
    case MaterialKind::Glass: return "glass";
    case MaterialKind::Emissive: return "emissive";
  }
  return "unknown";
}

namespace {

// One ceiling light, a table with one thing on it, and one or two more pieces.
void furnish_mini(RoomPlacer& placer, Pcg32& rng, MaterialPalette& palette, float ceiling) {
  placer.place_on_ceiling(make_ceiling_panel(rng, palette, ceiling), 0.0f);
  const Decor decor = rng.pick(std::vector<Decor>{Decor::MetalSphere, Decor::CeramicBowl, Decor::SmallBox});
  placer.place_on_floor(make_table(rng, palette, RoomPreset::Mini, {decor}));
  const int pieces = 1 + static_cast<int>(rng.below(2));
  for (int i = 0; i < pieces; ++i) {
    switch (rng.below(5)) {
      case 0: placer.place_against_wall(make_cabinet(rng, palette, RoomPreset::Mini)); break;
      case 1: placer.place_against_wall(make_shelf(rng, palette, RoomPreset::Mini, false)); break;
      case 2: placer.place_on_floor(make_stool(rng, palette)); break;
      case 3: placer.place_on_floor(make_crate(rng, palette, RoomPreset::Mini)); break;
      default: placer.place_on_floor(make_ball(rng, palette)); break;
    }
  }
}

// Everything that makes rendering and inverse rendering hard, essentials first: lights
// (panels and a 5 cm bright bulb), a mirror, thin panels and boards, glass, metals.
void furnish_hard(RoomPlacer& placer, Pcg32& rng, MaterialPalette& palette, float ceiling) {
  const int panels = 2 + static_cast<int>(rng.below(2));
  for (int i = 0; i < panels; ++i) placer.place_on_ceiling(make_ceiling_panel(rng, palette, ceiling), 1.0f);
  placer.place_on_ceiling(make_hanging_bulb(rng, palette, ceiling), 0.8f);
  placer.place_against_wall(make_wall_mirror(rng, palette, ceiling));
  placer.place_against_wall(make_wall_panel(rng, palette, ceiling));
  placer.place_on_floor(make_table(rng, palette, RoomPreset::Hard, {Decor::GlassVase, Decor::MetalSphere, Decor::CeramicBowl}));
  placer.place_against_wall(make_shelf(rng, palette, RoomPreset::Hard, true));
  placer.place_against_wall(make_cabinet(rng, palette, RoomPreset::Hard));
  placer.place_on_floor(make_floor_lamp(rng, palette));
  const int extras = 1 + static_cast<int>(rng.below(3));
  for (int i = 0; i < extras; ++i) {
    switch (rng.below(5)) {
      case 0: placer.place_on_floor(make_crate(rng, palette, RoomPreset::Hard)); break;
      case 1: placer.place_on_floor(make_ball(rng, palette)); break;
      case 2: placer.place_on_floor(make_stool(rng, palette)); break;
      case 3: placer.place_on_floor(make_glass_display(rng, palette)); break;
      default: placer.place_on_floor(make_table(rng, palette, RoomPreset::Hard, {Decor::GlassSphere, Decor::SmallBox})); break;
    }
  }
}

}  // namespace

void prune_unused_materials(RoomLayout& layout) {
  std::vector<int> remap(layout.materials.size(), -1);
  auto mark = [&](int m) { remap[m] = 0; };
  mark(layout.floor_material);
  mark(layout.ceiling_material);
  for (int m : layout.wall_materials) mark(m);
  for (const RoomObject& object : layout.objects)
    for (const RoomPart& part : object.parts) mark(part.material);

  std::vector<MaterialSpec> kept;
  for (size_t i = 0; i < layout.materials.size(); ++i) {
    if (remap[i] < 0) continue;
    remap[i] = static_cast<int>(kept.size());
    kept.push_back(layout.materials[i]);
  }
  layout.materials = std::move(kept);
  layout.floor_material = remap[layout.floor_material];
  layout.ceiling_material = remap[layout.ceiling_material];
  for (int& m : layout.wall_materials) m = remap[m];
  for (RoomObject& object : layout.objects)
    for (RoomPart& part : object.parts) part.material = remap[part.material];

  std::vector<int> texture_remap(layout.textures.size(), -1);
  for (const MaterialSpec& m : layout.materials) {
    if (m.base_color_texture >= 0) texture_remap[m.base_color_texture] = 0;
    if (m.metallic_roughness_texture >= 0) texture_remap[m.metallic_roughness_texture] = 0;
  }
  std::vector<TextureSpec> kept_textures;
  for (size_t i = 0; i < layout.textures.size(); ++i) {
    if (texture_remap[i] < 0) continue;
    texture_remap[i] = static_cast<int>(kept_textures.size());
    kept_textures.push_back(layout.textures[i]);
  }
  layout.textures = std::move(kept_textures);
  for (MaterialSpec& m : layout.materials) {
    if (m.base_color_texture >= 0) m.base_color_texture = texture_remap[m.base_color_texture];
    if (m.metallic_roughness_texture >= 0) m.metallic_roughness_texture = texture_remap[m.metallic_roughness_texture];
  }
}

RoomLayout plan_room(uint64_t seed, int index, RoomPreset preset) {
  if (index < 0) fail("room index {} is negative", index);
  const int salt = static_cast<int>(preset);
  RoomLayout layout;
  layout.preset = preset;
  layout.seed = seed;
  layout.index = index;

  Pcg32 shell_rng = room_rng(seed, index, salt, RoomStream::Shell);
  layout.shell = plan_shell(shell_rng, preset);

  Pcg32 texture_rng = room_rng(seed, index, salt, RoomStream::Textures);
  const uint64_t texture_seed_high = texture_rng.next_u32();  // two statements: operand order is unspecified
  const uint64_t texture_seed = (texture_seed_high << 32) | texture_rng.next_u32();
  MaterialPalette palette(room_rng(seed, index, salt, RoomStream::Materials), preset, texture_seed,
                          layout.materials, layout.textures);
  layout.floor_material = palette.get(MaterialRole::Floor);
  layout.ceiling_material = palette.get(MaterialRole::Ceiling);
  const int walls = static_cast<int>(layout.shell.outline().size());
  // Hard rooms paint one wall in an accent colour.
  const int accent = preset == RoomPreset::Hard ? static_cast<int>(shell_rng.below(static_cast<uint32_t>(walls))) : -1;
  for (int w = 0; w < walls; ++w) {
    layout.wall_materials.push_back(palette.get(w == accent ? MaterialRole::AccentWall : MaterialRole::Wall));
  }

  Pcg32 rng = room_rng(seed, index, salt, RoomStream::Furniture);
  RoomPlacer placer(layout.shell, layout.objects, rng);
  if (preset == RoomPreset::Hard) furnish_hard(placer, rng, palette, layout.shell.height);
  else furnish_mini(placer, rng, palette, layout.shell.height);

  // A crowded room gives up its last-placed (least essential) objects until enough open
  // space for the viewpoints remains. An empty room always has enough.
  while (!plan_viewpoints(layout, room_rng(seed, index, salt, RoomStream::Viewpoints))) {
    if (layout.objects.empty()) fail("room {} of seed {}: no room for {} viewpoints", index, seed, 1 + kMinCandidateViewpoints);
    layout.objects.pop_back();
  }
  prune_unused_materials(layout);
  return layout;
}

}  // namespace phyir::scenes
