#pragma once
// What the stability matrix's tests share (stability_matrix_test.cpp, and the probes'
// probe_stability_test.cpp): the material axes, scenes and case reports.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>
#include <vector>

#include "phyir/render/brdf.h"
#include "phyir/render/camera.h"
#include "test_scenes.h"

namespace phyir::render::stability {

constexpr float kRoughness[] = {0.0f, 1e-6f, 1e-3f, 0.05f, 0.5f, 1.0f};
constexpr float kMetalness[] = {0.0f, 0.5f, 1.0f};
constexpr float kBaseColor[] = {0.0f, 1.0f};

inline std::vector<BrdfParams> material_matrix() {
  std::vector<BrdfParams> out;
  for (float r : kRoughness)
    for (float m : kMetalness)
      for (float b : kBaseColor) out.push_back({glm::vec3(b), r, m});
  return out;
}

inline std::string describe(const BrdfParams& p) {
  char text[96];
  std::snprintf(text, sizeof text, "B=%g R=%g M=%g", p.base_color.x, p.roughness, p.metalness);
  return text;
}

inline void report(const char* what, uint64_t cases) {
  std::printf("[stability] %s: %llu cases\n", what, static_cast<unsigned long long>(cases));
  ::testing::Test::RecordProperty(what, std::to_string(cases));
}

inline CameraModel panorama(const glm::vec3& position, int width = 16, int height = 8) {
  CameraModel c;
  c.position = position;
  c.width = width;
  c.height = height;
  return c;
}

// A 4 x 3 x 4 m room of grey diffuse walls whose whole ceiling emits radiance 1 downwards:
// a large, uniform light, so every radiance in the room is a smooth function of position and
// direction (no small bright region that only a lucky sample finds). The test material
// covers the floor and a sphere.
inline scenes::Scene lit_room(const BrdfParams& p, float radiance = 1.0f) {
  scenes::Scene scene = test::make_box_room(glm::vec3(-2, 0, -2), glm::vec3(2, 3, 2), test::make_material(glm::vec3(0.5f)));
  const int m = test::add_material(scene, test::make_material(p.base_color, p.roughness, p.metalness, "test"));
  scene.meshes[2].material = m;  // the floor
  test::add_uv_sphere(scene, glm::vec3(0.6f, 0.6f, -0.5f), 0.5f, m, 24, 12);
  scene.meshes[3].material = test::add_material(scene, test::make_emitter(glm::vec3(radiance)));  // the ceiling
  return scene;
}

inline scenes::Scene scaled(scenes::Scene scene, float s) {
  scene.bounds = scenes::Bounds{};
  for (scenes::Mesh& m : scene.meshes)
    for (glm::vec3& p : m.positions) {
      p *= s;
      scene.bounds.extend(p);
    }
  return scene;
}

}  // namespace phyir::render::stability
