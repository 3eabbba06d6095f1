#pragma once
// Furniture, wall items and lights built from boxes, cylinders and spheres. Each builder
// works in the object's own frame: footprint centred on the origin, floor at y = 0, back at
// -z and front at +z (the side that faces the room when the piece stands against a wall).
#include <vector>

#include "generator/room/room_materials.h"
#include "generator/room/room_rng.h"
#include "phyir/scenes/room_layout.h"

namespace phyir::scenes {

// Small things that stand on a table top or a shelf board.
enum class Decor { GlassVase, GlassSphere, MetalSphere, CeramicBowl, SmallBox };

// Floor pieces.
RoomObject make_table(Pcg32& rng, MaterialPalette& palette, RoomPreset preset,
                      const std::vector<Decor>& decor);
// `thin_board`: one board is 1 cm thick (thin geometry for hard rooms).
RoomObject make_shelf(Pcg32& rng, MaterialPalette& palette, RoomPreset preset, bool thin_board);
RoomObject make_cabinet(Pcg32& rng, MaterialPalette& palette, RoomPreset preset);
RoomObject make_floor_lamp(Pcg32& rng, MaterialPalette& palette);
RoomObject make_stool(Pcg32& rng, MaterialPalette& palette);
RoomObject make_crate(Pcg32& rng, MaterialPalette& palette, RoomPreset preset);
RoomObject make_ball(Pcg32& rng, MaterialPalette& palette);
RoomObject make_glass_display(Pcg32& rng, MaterialPalette& palette);  // glass cube on a plinth

// Wall items: back face at z = -depth/2 goes against the wall.
RoomObject make_wall_mirror(Pcg32& rng, MaterialPalette& palette, float ceiling);
RoomObject make_wall_panel(Pcg32& rng, MaterialPalette& palette, float ceiling);  // 5 mm thick

// Ceiling items, hanging from y = ceiling.
RoomObject make_ceiling_panel(Pcg32& rng, MaterialPalette& palette, float ceiling);
RoomObject make_hanging_bulb(Pcg32& rng, MaterialPalette& palette, float ceiling);

// The object turned by quarter_turns * 90 degrees about +Y (counter-clockwise seen from
// above; one turn takes local +z to +x), then moved by offset.
RoomObject transformed(const RoomObject& local, int quarter_turns, const glm::vec3& offset);

}  // namespace phyir::scenes
