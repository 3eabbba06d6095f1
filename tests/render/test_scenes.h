#pragma once
// Small scenes built in code for the render tests: materials, quads, boxes, a box room
// and UV spheres, all in world space with the toolkit's conventions (metres, +Y up,
// triangles counter-clockwise seen from the side their geometric normal points to).
// Every add_* function appends ONE mesh and returns its index (= its Embree geometry id).
#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "phyir/scenes/scene.h"

namespace phyir::test {

// A one-sided diffuse-ish material (glTF factors).
inline scenes::Material make_material(const glm::vec3& base_color = glm::vec3(0.8f), float roughness = 1.0f,
                                      float metalness = 0.0f, const std::string& name = "material") {
  scenes::Material m;
  m.name = name;
  m.base_color_factor = glm::vec4(base_color, 1.0f);
  m.roughness_factor = roughness;
  m.metallic_factor = metalness;
  return m;
}

// A black emitter of radiance `emission` (emissive_factor = emission, strength 1).
inline scenes::Material make_emitter(const glm::vec3& emission, bool double_sided = false,
                                     const std::string& name = "emitter") {
  scenes::Material m = make_material(glm::vec3(0.0f), 1.0f, 0.0f, name);
  m.emissive_factor = emission;
  m.double_sided = double_sided;
  return m;
}

// A point light whose radiometric intensity is `watts` W/sr (glTF candela: x kLumensPerWatt).
inline scenes::PunctualLight make_point_light(float watts, const glm::vec3& position,
                                              const glm::vec3& color = glm::vec3(1.0f)) {
  scenes::PunctualLight light;
  light.type = scenes::PunctualLight::Type::Point;
  light.intensity = watts * scenes::PunctualLight::kLumensPerWatt;
  light.color = color;
  light.position = position;
  return light;
}

inline int add_material(scenes::Scene& scene, const scenes::Material& material) {
  scene.materials.push_back(material);
  return static_cast<int>(scene.materials.size()) - 1;
}

// A linear-data texture from row-major RGBA texels (row 0 = v = 0), nearest filtering so
// texel values can be read back exactly at texel centres.
inline int add_texture(scenes::Scene& scene, int width, int height, std::vector<glm::vec4> texels,
                       bool nearest = true, const std::string& name = "texture") {
  scenes::Texture t = scenes::Texture::from_linear(width, height, texels);  // stored as float: exact
  t.name = name;
  t.nearest = nearest;
  scene.textures.push_back(std::move(t));
  return static_cast<int>(scene.textures.size()) - 1;
}

inline int add_mesh(scenes::Scene& scene, scenes::Mesh mesh) {
  for (const glm::vec3& p : mesh.positions) scene.bounds.extend(p);
  scene.meshes.push_back(std::move(mesh));
  return static_cast<int>(scene.meshes.size()) - 1;
}

// Appends the quad {corner, corner + edge_u, corner + edge_u + edge_v, corner + edge_v}
// to `mesh` as two triangles. Front side (geometric normal) = normalize(cross(edge_u,
// edge_v)). UV (0,0) at `corner`, u along edge_u, v along edge_v; tangent = edge_u with
// w = +1 (bitangent cross(N, T) along edge_v for a rectangle).
inline void append_quad(scenes::Mesh& mesh, const glm::vec3& corner, const glm::vec3& edge_u,
                        const glm::vec3& edge_v) {
  const unsigned base = static_cast<unsigned>(mesh.positions.size());
  const glm::vec3 n = glm::normalize(glm::cross(edge_u, edge_v));
  const glm::vec4 t(glm::normalize(edge_u), 1.0f);
  const glm::vec3 p[4] = {corner, corner + edge_u, corner + edge_u + edge_v, corner + edge_v};
  const glm::vec2 uv[4] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  for (int i = 0; i < 4; ++i) {
    mesh.positions.push_back(p[i]);
    mesh.normals.push_back(n);
    mesh.tangents.push_back(t);
    mesh.texcoords0.push_back(uv[i]);
  }
  mesh.triangles.push_back(glm::uvec3(base, base + 1, base + 2));
  mesh.triangles.push_back(glm::uvec3(base, base + 2, base + 3));
}

// One quad as its own mesh (see append_quad for orientation and UVs).
inline int add_quad(scenes::Scene& scene, const glm::vec3& corner, const glm::vec3& edge_u,
                    const glm::vec3& edge_v, int material, const std::string& name = "quad") {
  scenes::Mesh mesh;
  mesh.name = name;
  mesh.material = material;
  append_quad(mesh, corner, edge_u, edge_v);
  return add_mesh(scene, std::move(mesh));
}

// The six faces of the box [min, max] as one closed mesh; normals point outward, or
// inward (into the box) when `inward`.
inline int add_box(scenes::Scene& scene, const glm::vec3& min, const glm::vec3& max, int material,
                   bool inward = false, const std::string& name = "box") {
  scenes::Mesh mesh;
  mesh.name = name;
  mesh.material = material;
  const glm::vec3 d = max - min;
  const glm::vec3 ex(d.x, 0, 0), ey(0, d.y, 0), ez(0, 0, d.z);
  // Each face as (corner, edge_u, edge_v) with cross(edge_u, edge_v) pointing outward.
  const glm::vec3 faces[6][3] = {
      {min, ez, ey},                     // -X
      {min + ex, ey, ez},                // +X
      {min, ex, ez},                     // -Y
      {min + ey, ez, ex},                // +Y
      {min, ey, ex},                     // -Z
      {min + ez, ex, ey},                // +Z
  };
  for (const auto& f : faces) {
    if (inward) {
      append_quad(mesh, f[0], f[2], f[1]);  // swapping the edges flips the winding
    } else {
      append_quad(mesh, f[0], f[1], f[2]);
    }
  }
  return add_mesh(scene, std::move(mesh));
}

// A punctual light of `watts` (W/sr on the axis for a point or spot, W/m^2 for a directional
// light), in the file's units (KHR_lights_punctual: candela, lux).
inline scenes::PunctualLight make_punctual_light(scenes::PunctualLight::Type type, float watts,
                                                 const glm::vec3& position, const glm::vec3& direction,
                                                 float inner_cone = 0.3f, float outer_cone = 0.5f,
                                                 const glm::vec3& color = glm::vec3(1.0f)) {
  scenes::PunctualLight l;
  l.type = type;
  l.intensity = watts * scenes::PunctualLight::kLumensPerWatt;
  l.color = color;
  l.position = position;
  l.direction = glm::normalize(direction);
  l.inner_cone_angle = inner_cone;
  l.outer_cone_angle = outer_cone;
  return l;
}

// The room [min, max] seen from inside: six walls, one mesh each, in the order
// -X, +X, floor (-Y), ceiling (+Y), -Z, +Z, all facing into the room, material 0 = wall.
inline scenes::Scene make_box_room(const glm::vec3& min, const glm::vec3& max,
                                   const scenes::Material& wall = make_material()) {
  scenes::Scene scene;
  scene.source = "test_scenes: box room";
  const int material = add_material(scene, wall);
  const glm::vec3 d = max - min;
  const glm::vec3 ex(d.x, 0, 0), ey(0, d.y, 0), ez(0, 0, d.z);
  add_quad(scene, min, ey, ez, material, "wall -X");
  add_quad(scene, min + ex, ez, ey, material, "wall +X");
  add_quad(scene, min, ez, ex, material, "floor");
  add_quad(scene, min + ey, ex, ez, material, "ceiling");
  add_quad(scene, min, ex, ey, material, "wall -Z");
  add_quad(scene, min + ez, ey, ex, material, "wall +Z");
  return scene;
}

// A UV sphere (`segments` around Y, `rings` from pole to pole) with smooth normals and
// equirect-like UVs (u around, v from the top pole). Normals and winding face outward,
// or inward when `inward`. Pole triangles are kept as emitted (no degenerate ones).
inline int add_uv_sphere(scenes::Scene& scene, const glm::vec3& centre, float radius, int material,
                         int segments = 32, int rings = 16, bool inward = false,
                         const std::string& name = "sphere") {
  scenes::Mesh mesh;
  mesh.name = name;
  mesh.material = material;
  const float pi = 3.14159265358979323846f;
  for (int r = 0; r <= rings; ++r) {
    const float theta = pi * static_cast<float>(r) / static_cast<float>(rings);
    for (int s = 0; s <= segments; ++s) {
      const float phi = 2.0f * pi * static_cast<float>(s) / static_cast<float>(segments);
      const glm::vec3 n(std::sin(theta) * std::sin(phi), std::cos(theta), std::sin(theta) * std::cos(phi));
      mesh.positions.push_back(centre + radius * n);
      mesh.normals.push_back(inward ? -n : n);
      mesh.texcoords0.push_back(glm::vec2(static_cast<float>(s) / segments, static_cast<float>(r) / rings));
    }
  }
  const unsigned stride = static_cast<unsigned>(segments + 1);
  auto tri = [&](unsigned a, unsigned b, unsigned c) {
    mesh.triangles.push_back(inward ? glm::uvec3(a, c, b) : glm::uvec3(a, b, c));
  };
  for (int r = 0; r < rings; ++r) {
    for (int s = 0; s < segments; ++s) {
      const unsigned i00 = r * stride + s, i01 = i00 + 1, i10 = i00 + stride, i11 = i10 + 1;
      // Seen from outside, with phi increasing and theta going down, (i00, i10, i11) is
      // counter-clockwise.
      if (r != 0) tri(i00, i10, i01);
      if (r != rings - 1) tri(i01, i10, i11);
    }
  }
  return add_mesh(scene, std::move(mesh));
}

// Lambert's formula: irradiance at the origin (normal n) from a polygon of radiance L
// (vertices relative to the origin, in order round the polygon).
inline double polygon_irradiance(const std::vector<glm::dvec3>& vertices, const glm::dvec3& n, double L) {
  double sum = 0.0;
  for (size_t i = 0; i < vertices.size(); ++i) {
    const glm::dvec3 a = glm::normalize(vertices[i]);
    const glm::dvec3 b = glm::normalize(vertices[(i + 1) % vertices.size()]);
    const double angle = std::acos(std::clamp(glm::dot(a, b), -1.0, 1.0));
    sum += angle * glm::dot(glm::normalize(glm::cross(a, b)), n);
  }
  return 0.5 * L * std::abs(sum);
}

// Solid angle of the triangle a, b, c seen from the origin (Van Oosterom & Strackee 1983).
inline double triangle_solid_angle(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
  const double la = glm::length(a), lb = glm::length(b), lc = glm::length(c);
  const double numerator = std::abs(glm::dot(a, glm::cross(b, c)));
  const double denominator = la * lb * lc + glm::dot(a, b) * lc + glm::dot(a, c) * lb + glm::dot(b, c) * la;
  return 2.0 * std::atan2(numerator, denominator);
}

// Solid angle of all of a mesh's triangles seen from r (overlaps counted twice).
inline double mesh_solid_angle(const scenes::Mesh& mesh, const glm::vec3& r) {
  double sum = 0.0;
  for (const glm::uvec3& t : mesh.triangles)
    sum += triangle_solid_angle(glm::dvec3(mesh.positions[t.x]) - glm::dvec3(r),
                                glm::dvec3(mesh.positions[t.y]) - glm::dvec3(r),
                                glm::dvec3(mesh.positions[t.z]) - glm::dvec3(r));
  return sum;
}

}  // namespace phyir::test
