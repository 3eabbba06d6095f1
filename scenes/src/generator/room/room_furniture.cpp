// Furniture builders. Sizes are those of real furniture (table tops at 72-76 cm, shelf
// boards 2 cm, cabinet tops 3 cm) so rooms read as rooms at metric scale. Random draws are
// one per statement: argument evaluation order is unspecified and rooms must be portable.
#include "generator/room/room_furniture.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace phyir::scenes {

namespace {

using glm::vec3;

// A box with its footprint centred on (cx, cz), from y0 up by size.y.
Box3 footprint_box(float cx, float cz, float y0, vec3 size) {
  return {{cx - 0.5f * size.x, y0, cz - 0.5f * size.z}, {cx + 0.5f * size.x, y0 + size.y, cz + 0.5f * size.z}};
}

void add_part(RoomObject& object, const std::string& name, Shape shape, const Box3& bounds, int material) {
  if (object.parts.empty()) object.bounds = bounds;
  else object.bounds.extend(bounds);
  object.parts.push_back({object.name + "_" + name, shape, bounds, material});
}

RoomObject start(const std::string& name, Mount mount) {
  RoomObject object;
  object.name = name;
  object.mount = mount;
  return object;
}

// Adds one decor item standing on a surface at height `y`, centred on (x, z), no wider than
// `room` in either direction.
void add_decor(RoomObject& object, Pcg32& rng, MaterialPalette& palette, Decor decor, float x,
               float z, float y, float room, const std::string& name) {
  switch (decor) {
    case Decor::GlassVase: {
      // A closed cylinder: transmission needs a closed surface to refract in and out.
      const float r = std::min(rng.uniform(0.06f, 0.09f), 0.5f * room);
      const float h = rng.uniform(0.2f, 0.3f);
      add_part(object, name, Shape::Cylinder, footprint_box(x, z, y, {2 * r, h, 2 * r}), palette.get(MaterialRole::Glass));
      return;
    }
    case Decor::GlassSphere: {
      const float r = std::min(rng.uniform(0.07f, 0.1f), 0.5f * room);
      add_part(object, name, Shape::Sphere, footprint_box(x, z, y, vec3(2 * r)), palette.get(MaterialRole::Glass));
      return;
    }
    case Decor::MetalSphere: {
      const float r = std::min(rng.uniform(0.06f, 0.1f), 0.5f * room);
      add_part(object, name, Shape::Sphere, footprint_box(x, z, y, vec3(2 * r)), palette.get(MaterialRole::PolishedMetal));
      return;
    }
    case Decor::CeramicBowl: {
      const float r = std::min(rng.uniform(0.08f, 0.12f), 0.5f * room);
      const float h = rng.uniform(0.06f, 0.09f);
      add_part(object, name, Shape::Cylinder, footprint_box(x, z, y, {2 * r, h, 2 * r}), palette.get(MaterialRole::Ceramic));
      return;
    }
    case Decor::SmallBox: {
      const float s = std::min(rng.uniform(0.12f, 0.22f), room);
      const float h = rng.uniform(0.08f, 0.2f);
      add_part(object, name, Shape::Box, footprint_box(x, z, y, {s, h, s}), palette.get(MaterialRole::Paint));
      return;
    }
  }
}

}  // namespace

RoomObject make_table(Pcg32& rng, MaterialPalette& palette, RoomPreset preset, const std::vector<Decor>& decor) {
  const bool hard = preset == RoomPreset::Hard;
  RoomObject table = start("table", Mount::Floor);
  const float w = hard ? rng.uniform(0.9f, 1.6f) : rng.uniform(0.8f, 1.2f);
  const float d = rng.uniform(0.6f, 0.9f);
  const float h = rng.uniform(0.72f, 0.76f);
  const float top = 0.04f;
  const bool lacquered = rng.chance(0.5f);
  const int top_material = palette.get(lacquered ? (hard ? MaterialRole::Lacquer : MaterialRole::Paint) : MaterialRole::Wood);
  add_part(table, "top", Shape::Box, footprint_box(0, 0, h - top, {w, top, d}), top_material);

  const bool metal_legs = rng.chance(hard ? 0.7f : 0.4f);
  const float leg = 0.05f;
  const float inset = 0.06f;  // legs stand this far in from the top's edges
  for (int i = 0; i < 4; ++i) {
    const float x = (i & 1 ? 1.0f : -1.0f) * (0.5f * w - inset);
    const float z = (i & 2 ? 1.0f : -1.0f) * (0.5f * d - inset);
    const Box3 bounds = footprint_box(x, z, 0, {leg, h - top, leg});
    if (metal_legs) add_part(table, "leg" + std::to_string(i), Shape::Cylinder, bounds, palette.get(MaterialRole::RoughMetal));
    else add_part(table, "leg" + std::to_string(i), Shape::Box, bounds, palette.get(MaterialRole::Wood));
  }

  // Decor in equal slots along the table, 3 cm clear of each slot's edges.
  const float slot = w / static_cast<float>(std::max<size_t>(decor.size(), 1));
  for (size_t k = 0; k < decor.size(); ++k) {
    const float x = -0.5f * w + slot * (static_cast<float>(k) + 0.5f);
    add_decor(table, rng, palette, decor[k], x, 0.0f, h, std::min(slot, d) - 0.06f, "decor" + std::to_string(k));
  }
  return table;
}

RoomObject make_shelf(Pcg32& rng, MaterialPalette& palette, RoomPreset preset, bool thin_board) {
  const bool hard = preset == RoomPreset::Hard;
  RoomObject shelf = start("shelf", Mount::Floor);
  const float w = rng.uniform(0.6f, 1.2f);
  const float d = rng.uniform(0.28f, 0.4f);
  const float h = hard ? rng.uniform(1.2f, 2.0f) : rng.uniform(1.0f, 1.6f);
  const int material = palette.get(rng.chance(0.5f) ? MaterialRole::Wood : MaterialRole::Paint);
  const float side = 0.02f, board = 0.02f, back = 0.008f;
  add_part(shelf, "side_left", Shape::Box, {{-0.5f * w, 0, -0.5f * d}, {-0.5f * w + side, h, 0.5f * d}}, material);
  add_part(shelf, "side_right", Shape::Box, {{0.5f * w - side, 0, -0.5f * d}, {0.5f * w, h, 0.5f * d}}, material);
  add_part(shelf, "back", Shape::Box, {{-0.5f * w + side, 0, -0.5f * d}, {0.5f * w - side, h, -0.5f * d + back}}, material);

  // Boards from 5 cm above the floor to the top, at least 30 cm apart.
  const int gaps = std::clamp(static_cast<int>((h - 0.05f) / 0.35f), 2, 5);
  const float spacing = (h - 0.05f - board) / static_cast<float>(gaps);
  const int thin = thin_board ? 1 + static_cast<int>(rng.below(static_cast<uint32_t>(gaps - 1))) : -1;
  const float inner_w = w - 2 * side;
  for (int k = 0; k <= gaps; ++k) {
    const float y = 0.05f + spacing * static_cast<float>(k);
    const float t = k == thin ? 0.01f : board;  // the 1 cm board: thin geometry
    add_part(shelf, "board" + std::to_string(k), Shape::Box,
             {{-0.5f * w + side, y, -0.5f * d + back}, {0.5f * w - side, y + t, 0.5f * d}}, material);
    if (k == gaps || !rng.chance(0.6f)) continue;
    // One item per board, in a random third of it, clear of the board above.
    const std::vector<Decor> options = hard ? std::vector<Decor>{Decor::SmallBox, Decor::CeramicBowl, Decor::MetalSphere}
                                            : std::vector<Decor>{Decor::SmallBox, Decor::CeramicBowl};
    const Decor item = rng.pick(options);
    const float third = static_cast<float>(rng.below(3));
    const float x = -0.5f * inner_w + inner_w * (third + 0.5f) / 3.0f;
    const float room = std::min({inner_w / 3.0f - 0.04f, d - back - 0.06f, spacing - board - 0.08f});
    add_decor(shelf, rng, palette, item, x, 0.5f * back, y + t, room, "item" + std::to_string(k));
  }
  return shelf;
}

RoomObject make_cabinet(Pcg32& rng, MaterialPalette& palette, RoomPreset preset) {
  const bool hard = preset == RoomPreset::Hard;
  RoomObject cabinet = start("cabinet", Mount::Floor);
  const float w = rng.uniform(0.6f, 1.4f);
  const float d = rng.uniform(0.4f, 0.6f);
  const float h = rng.uniform(0.7f, 0.95f);
  const float top = 0.03f;
  const int body = palette.get(rng.chance(0.5f) ? MaterialRole::Wood : MaterialRole::Paint);
  add_part(cabinet, "body", Shape::Box, footprint_box(0, 0, 0, {w, h - top, d}), body);
  // A worn metal top carries the metallicRoughness texture in hard rooms.
  const int top_material = palette.get(hard ? MaterialRole::WornMetal : MaterialRole::Lacquer);
  add_part(cabinet, "top", Shape::Box, footprint_box(0, 0.005f, h - top, {w + 0.02f, top, d + 0.01f}), top_material);

  const int doors = w > 0.9f ? 2 : 1;
  const int handle_material = palette.get(hard ? MaterialRole::PolishedMetal : MaterialRole::RoughMetal);
  const float r = 0.008f, length = 0.12f;
  const float yc = 0.6f * (h - top);
  for (int i = 0; i < doors; ++i) {
    const float x = doors == 1 ? 0.0f : (i == 0 ? -0.25f : 0.25f) * w;
    add_part(cabinet, "handle" + std::to_string(i), Shape::Cylinder,
             {{x - r, yc - 0.5f * length, 0.5f * d}, {x + r, yc + 0.5f * length, 0.5f * d + 2 * r}}, handle_material);
  }
  return cabinet;
}

RoomObject make_floor_lamp(Pcg32& rng, MaterialPalette& palette) {
  RoomObject lamp = start("floor_lamp", Mount::Floor);
  const float base_r = rng.uniform(0.14f, 0.18f);
  const float pole_h = rng.uniform(1.3f, 1.5f);
  const float shade_r = rng.uniform(0.12f, 0.16f);
  const float base_h = 0.03f, pole_r = 0.012f;
  add_part(lamp, "base", Shape::Cylinder, footprint_box(0, 0, 0, {2 * base_r, base_h, 2 * base_r}), palette.get(MaterialRole::RoughMetal));
  add_part(lamp, "pole", Shape::Cylinder, footprint_box(0, 0, base_h, {2 * pole_r, pole_h, 2 * pole_r}), palette.get(MaterialRole::PolishedMetal));
  add_part(lamp, "shade", Shape::Sphere, footprint_box(0, 0, base_h + pole_h, vec3(2 * shade_r)), palette.get(MaterialRole::LampShade));
  return lamp;
}

RoomObject make_stool(Pcg32& rng, MaterialPalette& palette) {
  RoomObject stool = start("stool", Mount::Floor);
  const float seat_r = rng.uniform(0.16f, 0.2f);
  const int seat = palette.get(rng.chance(0.5f) ? MaterialRole::Lacquer : MaterialRole::Fabric);
  add_part(stool, "foot", Shape::Cylinder, footprint_box(0, 0, 0, {0.4f, 0.02f, 0.4f}), palette.get(MaterialRole::RoughMetal));
  add_part(stool, "post", Shape::Cylinder, footprint_box(0, 0, 0.02f, {0.06f, 0.41f, 0.06f}), palette.get(MaterialRole::RoughMetal));
  add_part(stool, "seat", Shape::Cylinder, footprint_box(0, 0, 0.43f, {2 * seat_r, 0.04f, 2 * seat_r}), seat);
  return stool;
}

RoomObject make_crate(Pcg32& rng, MaterialPalette& palette, RoomPreset preset) {
  RoomObject crate = start("crate", Mount::Floor);
  const float s = rng.uniform(0.3f, 0.6f);
  const float h = rng.uniform(0.25f, 0.5f);
  const MaterialRole role = preset == RoomPreset::Hard ? MaterialRole::Checker
                                                       : (rng.chance(0.5f) ? MaterialRole::Wood : MaterialRole::Fabric);
  add_part(crate, "box", Shape::Box, footprint_box(0, 0, 0, {s, h, s}), palette.get(role));
  return crate;
}

RoomObject make_ball(Pcg32& rng, MaterialPalette& palette) {
  RoomObject ball = start("ball", Mount::Floor);
  const float r = rng.uniform(0.1f, 0.25f);
  const MaterialRole role = rng.pick(std::vector<MaterialRole>{MaterialRole::Lacquer, MaterialRole::Ceramic, MaterialRole::PolishedMetal});
  add_part(ball, "sphere", Shape::Sphere, footprint_box(0, 0, 0, vec3(2 * r)), palette.get(role));
  return ball;
}

RoomObject make_glass_display(Pcg32& rng, MaterialPalette& palette) {
  RoomObject display = start("glass_display", Mount::Floor);
  const float plinth_h = rng.uniform(0.45f, 0.6f);
  const float cube = rng.uniform(0.25f, 0.32f);
  add_part(display, "plinth", Shape::Box, footprint_box(0, 0, 0, {0.4f, plinth_h, 0.4f}), palette.get(MaterialRole::Ceramic));
  add_part(display, "glass_box", Shape::Box, footprint_box(0, 0, plinth_h, vec3(cube)), palette.get(MaterialRole::Glass));
  return display;
}

RoomObject make_wall_mirror(Pcg32& rng, MaterialPalette& palette, float ceiling) {
  RoomObject mirror = start("wall_mirror", Mount::Wall);
  const float w = rng.uniform(0.5f, 1.0f);
  const float h = rng.uniform(0.7f, 1.2f);
  const float bottom = std::min(rng.uniform(0.8f, 1.0f), ceiling - 0.2f - h);
  add_part(mirror, "glass", Shape::Box, footprint_box(0, 0, bottom, {w, h, 0.01f}), palette.get(MaterialRole::Mirror));
  return mirror;
}

RoomObject make_wall_panel(Pcg32& rng, MaterialPalette& palette, float ceiling) {
  RoomObject panel = start("wall_panel", Mount::Wall);
  const float w = rng.uniform(0.8f, 1.6f);
  const float h = rng.uniform(0.5f, 1.0f);
  const float bottom = std::min(rng.uniform(0.9f, 1.3f), ceiling - 0.2f - h);
  const MaterialRole role = rng.pick(std::vector<MaterialRole>{MaterialRole::Wood, MaterialRole::Checker, MaterialRole::WornMetal});
  // 5 mm thick: thin geometry that shadow rays and BVH builders must not lose.
  add_part(panel, "board", Shape::Box, footprint_box(0, 0, bottom, {w, h, 0.005f}), palette.get(role));
  return panel;
}

RoomObject make_ceiling_panel(Pcg32& rng, MaterialPalette& palette, float ceiling) {
  RoomObject light = start("ceiling_light", Mount::Ceiling);
  vec3 size(0.0f, 0.03f, 0.0f);
  if (rng.chance(0.3f)) {
    size.x = 1.2f;  // a long strip light
    size.z = 0.3f;
  } else {
    size.x = rng.uniform(0.5f, 0.8f);
    size.z = size.x;
  }
  // 1 mm below the ceiling: no coplanar faces with it. Only the 2 mm diffuser under a
  // non-emissive housing glows, so no light leaks up into the gap above the fixture (it
  // would light a hidden strip of ceiling brightly and feed fireflies), and renderers that
  // emit from both faces (Cycles) see the same light as one-sided ones.
  const float bottom = ceiling - 0.001f - size.y, diffuser = 0.002f;
  add_part(light, "diffuser", Shape::Box, footprint_box(0, 0, bottom, {size.x, diffuser, size.z}),
           palette.get(MaterialRole::LightPanel));
  add_part(light, "housing", Shape::Box, footprint_box(0, 0, bottom + diffuser, {size.x, size.y - diffuser, size.z}),
           palette.get(MaterialRole::Ceiling));
  return light;
}

RoomObject make_hanging_bulb(Pcg32& rng, MaterialPalette& palette, float ceiling) {
  RoomObject bulb = start("hanging_bulb", Mount::Ceiling);
  const float drop = rng.uniform(0.4f, 0.7f);  // ceiling to bulb centre
  const float r = 0.05f, cord_r = 0.003f;
  const float centre = ceiling - drop;
  add_part(bulb, "bulb", Shape::Sphere, footprint_box(0, 0, centre - r, vec3(2 * r)), palette.get(MaterialRole::BrightBulb));
  add_part(bulb, "cord", Shape::Cylinder,
           footprint_box(0, 0, centre + r, {2 * cord_r, ceiling - 0.001f - centre - r, 2 * cord_r}),
           palette.get(MaterialRole::RoughMetal));
  return bulb;
}

namespace {

vec3 quarter_turn(const vec3& p, int turns) {
  switch (((turns % 4) + 4) % 4) {
    case 1: return {p.z, p.y, -p.x};
    case 2: return {-p.x, p.y, -p.z};
    case 3: return {-p.z, p.y, p.x};
    default: return p;
  }
}

Box3 turned_box(const Box3& b, int turns, const vec3& offset) {
  const vec3 a = quarter_turn(b.min, turns), c = quarter_turn(b.max, turns);
  return {glm::min(a, c) + offset, glm::max(a, c) + offset};
}

}  // namespace

RoomObject transformed(const RoomObject& local, int quarter_turns, const vec3& offset) {
  RoomObject placed = local;
  placed.bounds = turned_box(local.bounds, quarter_turns, offset);
  for (RoomPart& part : placed.parts) part.bounds = turned_box(part.bounds, quarter_turns, offset);
  return placed;
}

}  // namespace phyir::scenes
