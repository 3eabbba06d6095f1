// The apartment's shell meshed on the grid of every coordinate the plan uses: each cell is
// solid or empty (ApartmentPlan::is_solid at its centre), and every face between a solid
// and an empty cell becomes a quad facing the empty one. All plan rectangles are on grid
// lines, so the classification is exact and the surface closed.
#include "phyir/scenes/apartment_shell.h"

#include <algorithm>
#include <array>
#include <map>

namespace phyir::scenes {

const char* shell_surface_name(ShellSurface surface) {
  switch (surface) {
    case ShellSurface::Floor: return "floor";
    case ShellSurface::Ceiling: return "ceiling";
    case ShellSurface::Wall: return "wall";
    case ShellSurface::Facade: return "facade";
    case ShellSurface::Roof: return "roof";
  }
  return "surface";
}

namespace {

std::vector<float> unique_sorted(std::vector<float> v) {
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end(), [](float a, float b) { return b - a < 1e-5f; }), v.end());
  return v;
}

struct Grid {
  std::array<std::vector<float>, 3> lines;  // x, y, z
  std::vector<char> solid;                  // per cell, x fastest

  int cells(int axis) const { return static_cast<int>(lines[axis].size()) - 1; }
  bool in_range(const glm::ivec3& c) const {
    for (int a = 0; a < 3; ++a)
      if (c[a] < 0 || c[a] >= cells(a)) return false;
    return true;
  }
  bool is_solid(const glm::ivec3& c) const {
    return in_range(c) && solid[(size_t(c.z) * cells(1) + c.y) * cells(0) + c.x] != 0;
  }
  glm::vec3 centre(const glm::ivec3& c) const {
    glm::vec3 p;
    for (int a = 0; a < 3; ++a) p[a] = c[a] < 0 ? lines[a].front() - 1.0f
                                      : c[a] >= cells(a) ? lines[a].back() + 1.0f
                                                         : 0.5f * (lines[a][c[a]] + lines[a][c[a] + 1]);
    return p;
  }
};

Grid make_grid(const ApartmentPlan& plan) {
  std::array<std::vector<float>, 3> raw;
  auto add_rect = [&](const Rect2& r) {
    raw[0].insert(raw[0].end(), {r.min.x, r.max.x});
    raw[2].insert(raw[2].end(), {r.min.y, r.max.y});
  };
  add_rect(plan.outline());
  add_rect(plan.interior);
  raw[1] = {-plan.slab, 0.0f, plan.height, plan.height + plan.slab};
  for (const ApartmentRoom& room : plan.rooms) add_rect(room.floor);
  for (const WallOpening& o : plan.openings) {
    add_rect(o.footprint);
    raw[1].insert(raw[1].end(), {o.bottom, o.top});
  }
  Grid grid;
  for (int a = 0; a < 3; ++a) grid.lines[a] = unique_sorted(raw[a]);
  grid.solid.resize(size_t(grid.cells(0)) * grid.cells(1) * grid.cells(2));
  for (int z = 0; z < grid.cells(2); ++z)
    for (int y = 0; y < grid.cells(1); ++y)
      for (int x = 0; x < grid.cells(0); ++x)
        grid.solid[(size_t(z) * grid.cells(1) + y) * grid.cells(0) + x] = plan.is_solid(grid.centre({x, y, z}));
  return grid;
}

// Which piece a face belongs to, from the empty cell it faces and its normal.
std::pair<int, ShellSurface> classify(const ApartmentPlan& plan, const glm::vec3& empty_centre, const glm::vec3& n) {
  const glm::vec2 xz(empty_centre.x, empty_centre.z);
  const bool inside = plan.outline().contains(xz) && empty_centre.y > 0.0f && empty_centre.y < plan.height;
  if (!inside) return {-1, n.y > 0.5f ? ShellSurface::Roof : ShellSurface::Facade};
  int room = plan.room_at(xz);
  if (room < 0) {  // a reveal: the face of an opening's hole
    for (const WallOpening& o : plan.openings)
      if (o.footprint.contains(xz)) room = o.room;
  }
  if (room < 0) return {-1, ShellSurface::Facade};
  if (n.y > 0.5f) return {room, ShellSurface::Floor};
  if (n.y < -0.5f) return {room, ShellSurface::Ceiling};
  return {room, ShellSurface::Wall};
}

void add_quad(ShellPiece& piece, const Grid& grid, const glm::ivec3& cell, int axis, int side) {
  // The face at the cell's `side` (0: low, 1: high) across `axis`; u and v span it so that
  // (u x v) points along the outward normal.
  const int u_axis = (axis + 1) % 3, v_axis = (axis + 2) % 3;
  const float w = grid.lines[axis][cell[axis] + side];
  const float u0 = grid.lines[u_axis][cell[u_axis]], u1 = grid.lines[u_axis][cell[u_axis] + 1];
  const float v0 = grid.lines[v_axis][cell[v_axis]], v1 = grid.lines[v_axis][cell[v_axis] + 1];
  glm::vec3 n(0.0f);
  n[axis] = side == 1 ? 1.0f : -1.0f;
  auto corner = [&](float u, float v) {
    glm::vec3 p;
    p[axis] = w, p[u_axis] = u, p[v_axis] = v;
    return p;
  };
  const uint32_t base = static_cast<uint32_t>(piece.positions.size());
  for (const glm::vec2& uv : {glm::vec2(u0, v0), glm::vec2(u1, v0), glm::vec2(u1, v1), glm::vec2(u0, v1)}) {
    const glm::vec3 p = corner(uv.x, uv.y);
    piece.positions.push_back(p);
    piece.normals.push_back(n);
    // Planar texture coordinates in metres: floors (x, z); walls (along the wall, height).
    piece.uvs.push_back(axis == 1 ? glm::vec2(p.x, p.z) : glm::vec2(axis == 0 ? p.z : p.x, -p.y));
  }
  const bool ccw = side == 1;  // u x v is +axis
  const std::array<uint32_t, 6> order = ccw ? std::array<uint32_t, 6>{0, 1, 2, 0, 2, 3}
                                            : std::array<uint32_t, 6>{0, 2, 1, 0, 3, 2};
  for (uint32_t i : order) piece.indices.push_back(base + i);
}

}  // namespace

std::vector<ShellPiece> mesh_apartment_shell(const ApartmentPlan& plan) {
  const Grid grid = make_grid(plan);
  std::map<std::pair<int, int>, ShellPiece> pieces;  // (room + 1, surface): outside first
  for (int z = 0; z < grid.cells(2); ++z)
    for (int y = 0; y < grid.cells(1); ++y)
      for (int x = 0; x < grid.cells(0); ++x) {
        const glm::ivec3 cell(x, y, z);
        if (!grid.is_solid(cell)) continue;
        for (int axis = 0; axis < 3; ++axis)
          for (int side = 0; side < 2; ++side) {
            glm::ivec3 next = cell;
            next[axis] += side == 1 ? 1 : -1;
            if (grid.is_solid(next)) continue;
            glm::vec3 n(0.0f);
            n[axis] = side == 1 ? 1.0f : -1.0f;
            const auto [room, surface] = classify(plan, grid.centre(next), n);
            ShellPiece& piece = pieces[{room + 1, static_cast<int>(surface)}];
            piece.room = room;
            piece.surface = surface;
            add_quad(piece, grid, cell, axis, side);
          }
      }
  // Rooms in plan order, then the outside.
  std::vector<ShellPiece> out;
  for (auto& [key, piece] : pieces)
    if (key.first > 0) out.push_back(std::move(piece));
  for (auto& [key, piece] : pieces)
    if (key.first == 0) out.push_back(std::move(piece));
  return out;
}

}  // namespace phyir::scenes
