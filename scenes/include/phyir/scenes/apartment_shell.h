#pragma once
// The apartment's walls, floors, ceilings and roof as triangles: the boundary of the solid
// the plan describes (ApartmentPlan::is_solid), so doors and windows are real holes with
// reveals, and the building is closed everywhere else.
#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

#include "phyir/scenes/apartment_plan.h"

namespace phyir::scenes {

enum class ShellSurface { Floor, Ceiling, Wall, Facade, Roof };
constexpr int kShellSurfaceCount = 5;
const char* shell_surface_name(ShellSurface surface);  // "floor", "ceiling", ...

// The faces of one surface of one room (room -1: the outside of the building), with
// planar texture coordinates in metres (floors and ceilings: x, z; walls: along, y).
struct ShellPiece {
  int room = -1;
  ShellSurface surface = ShellSurface::Wall;
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;  // facing out of the solid, into the room or the outside
  std::vector<glm::vec2> uvs;
  std::vector<uint32_t> indices;   // counter-clockwise seen from the normal's side
};

// Non-empty pieces in a fixed order: rooms in plan order (floor, ceiling, wall), then the
// outside (facade, roof). Reveals of an opening belong to the walls of its `room`.
std::vector<ShellPiece> mesh_apartment_shell(const ApartmentPlan& plan);

}  // namespace phyir::scenes
