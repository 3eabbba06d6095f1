#pragma once
// Triangle meshes of the room's primitives. Normals are unit length and point out of solids
// and into the room for the shell; triangles wind counter-clockwise seen from the side their
// normal points to (glTF's front face). Texture coordinates are in metres times `uv_scale`
// (texture repeats per metre), so tiled textures keep their size on every object.
#include <cstdint>
#include <vector>

#include "phyir/scenes/room_layout.h"

namespace phyir::scenes {

struct MeshData {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;
  std::vector<glm::vec2> texcoords;
  std::vector<uint32_t> indices;  // three per triangle

  size_t triangle_count() const { return indices.size() / 3; }
  void append(const MeshData& other);
};

// Closed meshes: six faces with their own vertices (sharp edges).
MeshData box_mesh(const Box3& box, float uv_scale);
// Standing along Y, inscribed in the box's footprint; side plus both caps.
MeshData cylinder_mesh(const Box3& bounds, int segments, float uv_scale);
// Centred in the box, radius half its smallest side; `segments` around, segments/2 rings.
MeshData sphere_mesh(const Box3& bounds, int segments, float uv_scale);

// Shell surfaces (one-sided, facing into the room).
MeshData floor_mesh(const RoomShell& shell, float uv_scale);
MeshData ceiling_mesh(const RoomShell& shell, float uv_scale);
MeshData wall_mesh(const RoomShell& shell, int wall, float uv_scale);

}  // namespace phyir::scenes
