// Box, cylinder, sphere and shell meshes.
#include "generator/room/room_primitives.h"

#include <algorithm>
#include <cmath>

#include "phyir/core/safe_math.h"

namespace phyir::scenes {

using glm::vec2;
using glm::vec3;

void MeshData::append(const MeshData& other) {
  const auto base = static_cast<uint32_t>(positions.size());
  positions.insert(positions.end(), other.positions.begin(), other.positions.end());
  normals.insert(normals.end(), other.normals.begin(), other.normals.end());
  texcoords.insert(texcoords.end(), other.texcoords.begin(), other.texcoords.end());
  for (uint32_t i : other.indices) indices.push_back(base + i);
}

namespace {

uint32_t add_vertex(MeshData& mesh, const vec3& p, const vec3& n, const vec2& uv) {
  mesh.positions.push_back(p);
  mesh.normals.push_back(glm::normalize(n));
  mesh.texcoords.push_back(uv);
  return static_cast<uint32_t>(mesh.positions.size() - 1);
}

void add_triangle(MeshData& mesh, uint32_t a, uint32_t b, uint32_t c) {
  mesh.indices.insert(mesh.indices.end(), {a, b, c});
}

// A planar quad with corners origin + {0, u, u + v, v}; cross(u, v) is its normal, so the
// corners run counter-clockwise seen from the front.
void add_quad(MeshData& mesh, const vec3& origin, const vec3& u, const vec3& v, float uv_scale) {
  const vec3 n = glm::normalize(glm::cross(u, v));
  const vec3 du = glm::normalize(u), dv = glm::normalize(v);
  const vec3 corners[4] = {origin, origin + u, origin + u + v, origin + v};
  uint32_t id[4];
  for (int i = 0; i < 4; ++i) {
    // Planar mapping in metres along the quad's own axes.
    id[i] = add_vertex(mesh, corners[i], n, uv_scale * vec2(glm::dot(corners[i], du), glm::dot(corners[i], dv)));
  }
  add_triangle(mesh, id[0], id[1], id[2]);
  add_triangle(mesh, id[0], id[2], id[3]);
}

// Direction around the Y axis for step i of `segments`. Angles run clockwise seen from
// above (x towards -z), which makes the (i, i+1) order counter-clockwise seen from outside.
vec3 around(int i, int segments) {
  const float phi = kTwoPi * static_cast<float>(i % segments) / static_cast<float>(segments);
  return {std::cos(phi), 0.0f, -std::sin(phi)};
}

}  // namespace

MeshData box_mesh(const Box3& b, float uv_scale) {
  MeshData mesh;
  const vec3 s = b.size();
  const vec3 X(s.x, 0, 0), Y(0, s.y, 0), Z(0, 0, s.z);
  const vec3& lo = b.min;
  const vec3 hi = b.max;
  add_quad(mesh, {hi.x, lo.y, hi.z}, -Z, Y, uv_scale);  // +x
  add_quad(mesh, {lo.x, lo.y, lo.z}, Z, Y, uv_scale);   // -x
  add_quad(mesh, {lo.x, lo.y, hi.z}, X, Y, uv_scale);   // +z
  add_quad(mesh, {hi.x, lo.y, lo.z}, -X, Y, uv_scale);  // -z
  add_quad(mesh, {lo.x, hi.y, hi.z}, X, -Z, uv_scale);  // +y
  add_quad(mesh, {lo.x, lo.y, lo.z}, X, Z, uv_scale);   // -y
  return mesh;
}

MeshData cylinder_mesh(const Box3& b, int segments, float uv_scale) {
  MeshData mesh;
  const vec3 c = b.centre();
  const float r = 0.5f * std::min(b.size().x, b.size().z);
  // Side: columns 0..segments, the last repeating the first with u continued (no seam jump).
  std::vector<uint32_t> bottom, top;
  for (int i = 0; i <= segments; ++i) {
    const vec3 d = around(i, segments);
    const float u = uv_scale * r * kTwoPi * static_cast<float>(i) / static_cast<float>(segments);
    bottom.push_back(add_vertex(mesh, {c.x + r * d.x, b.min.y, c.z + r * d.z}, d, {u, uv_scale * b.min.y}));
    top.push_back(add_vertex(mesh, {c.x + r * d.x, b.max.y, c.z + r * d.z}, d, {u, uv_scale * b.max.y}));
  }
  for (int i = 0; i < segments; ++i) {
    add_triangle(mesh, bottom[i], bottom[i + 1], top[i + 1]);
    add_triangle(mesh, bottom[i], top[i + 1], top[i]);
  }
  // Caps: fans around a centre vertex, planar mapping.
  for (const float y : {b.min.y, b.max.y}) {
    const bool up = y == b.max.y;
    const vec3 n(0.0f, up ? 1.0f : -1.0f, 0.0f);
    const uint32_t centre = add_vertex(mesh, {c.x, y, c.z}, n, uv_scale * vec2(c.x, c.z));
    std::vector<uint32_t> ring;
    for (int i = 0; i < segments; ++i) {
      const vec3 p(c.x + r * around(i, segments).x, y, c.z + r * around(i, segments).z);
      ring.push_back(add_vertex(mesh, p, n, uv_scale * vec2(p.x, p.z)));
    }
    for (int i = 0; i < segments; ++i) {
      const uint32_t a = ring[i], next = ring[(i + 1) % segments];
      if (up) add_triangle(mesh, centre, a, next);
      else add_triangle(mesh, centre, next, a);
    }
  }
  return mesh;
}

MeshData sphere_mesh(const Box3& b, int segments, float uv_scale) {
  MeshData mesh;
  const vec3 c = b.centre();
  const vec3 s = b.size();
  const float r = 0.5f * std::min({s.x, s.y, s.z});
  const int rings = std::max(segments / 2, 2);
  // grid[j][i]: ring j from the top pole (j = 0) to the bottom pole (j = rings).
  std::vector<std::vector<uint32_t>> grid(rings + 1);
  for (int j = 0; j <= rings; ++j) {
    const float theta = kPi * static_cast<float>(j) / static_cast<float>(rings);
    for (int i = 0; i <= segments; ++i) {
      vec3 d;
      if (j == 0) d = {0.0f, 1.0f, 0.0f};  // exact poles: sin(pi) is not 0 in floats
      else if (j == rings) d = {0.0f, -1.0f, 0.0f};
      else d = std::sin(theta) * around(i, segments) + vec3(0.0f, std::cos(theta), 0.0f);
      const vec2 uv = uv_scale * r * vec2(kTwoPi * static_cast<float>(i) / static_cast<float>(segments), theta);
      grid[j].push_back(add_vertex(mesh, c + r * d, d, uv));
    }
  }
  for (int j = 0; j < rings; ++j) {
    for (int i = 0; i < segments; ++i) {
      const uint32_t upper = grid[j][i], upper_next = grid[j][i + 1];
      const uint32_t lower = grid[j + 1][i], lower_next = grid[j + 1][i + 1];
      // At the poles one triangle of the quad has zero area: leave it out.
      if (j != rings - 1) add_triangle(mesh, lower, lower_next, upper_next);
      if (j != 0) add_triangle(mesh, lower, upper_next, upper);
    }
  }
  return mesh;
}

namespace {

// The floor polygon as a fan from the shell's fan corner (it sees every other corner of a
// rectangle or an L), at height y, each triangle wound to face `normal`.
MeshData horizontal_mesh(const RoomShell& shell, float y, const vec3& normal, float uv_scale) {
  MeshData mesh;
  const std::vector<vec2> corners = shell.outline();
  std::vector<uint32_t> id;
  for (const vec2& q : corners) id.push_back(add_vertex(mesh, {q.x, y, q.y}, normal, uv_scale * q));
  const size_t n = corners.size();
  const size_t f = static_cast<size_t>(shell.fan_corner());
  for (size_t k = 1; k + 1 < n; ++k) {
    uint32_t a = id[f], b = id[(f + k) % n], c = id[(f + k + 1) % n];
    const vec3 face = glm::cross(mesh.positions[b] - mesh.positions[a], mesh.positions[c] - mesh.positions[a]);
    if (glm::dot(face, normal) < 0.0f) std::swap(b, c);
    add_triangle(mesh, a, b, c);
  }
  return mesh;
}

}  // namespace

MeshData floor_mesh(const RoomShell& shell, float uv_scale) {
  return horizontal_mesh(shell, 0.0f, {0.0f, 1.0f, 0.0f}, uv_scale);
}

MeshData ceiling_mesh(const RoomShell& shell, float uv_scale) {
  return horizontal_mesh(shell, shell.height, {0.0f, -1.0f, 0.0f}, uv_scale);
}

MeshData wall_mesh(const RoomShell& shell, int wall, float uv_scale) {
  const std::vector<vec2> corners = shell.outline();
  const vec2 a = corners[wall];
  const vec2 b = corners[(wall + 1) % corners.size()];
  const vec2 inward = shell.wall_inward_normal(wall);
  const vec3 up(0.0f, shell.height, 0.0f);
  vec3 start(a.x, 0.0f, a.y), along(b.x - a.x, 0.0f, b.y - a.y);
  // cross(along, up) must point into the room; otherwise run the wall from b to a.
  if (glm::dot(glm::cross(along, up), vec3(inward.x, 0.0f, inward.y)) < 0.0f) {
    start = {b.x, 0.0f, b.y};
    along = -along;
  }
  MeshData mesh;
  add_quad(mesh, start, along, up, uv_scale);
  return mesh;
}

}  // namespace phyir::scenes
