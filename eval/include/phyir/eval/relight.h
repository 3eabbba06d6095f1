#pragma once
// Relighting error (paper sec. 4.2, Table 5, D.3): a sphere of each of Table 10's materials
// is rendered by the path tracer with a light probe as its only light (an equirect
// environment map, world-aligned as every probe is), once under the predicted probe and once
// under the ground-truth one, with the same seed (so most Monte-Carlo noise cancels in the
// difference); MAE and RMSE over the sphere's pixels and the three channels.
//
// The camera: perspective, size x size pixels, at (0, 0, 3) looking along -Z at a unit sphere
// at the origin, field of view 1.08 x the sphere's angular diameter.
#include <array>
#include <cstdint>
#include <string>

#include <glm/glm.hpp>

#include "phyir/core/image.h"
#include "phyir/scenes/scene.h"

namespace phyir::eval {

struct SphereMaterial {
  std::string key;    // diffuse | matte_silver | mirror_silver
  std::string label;  // as the paper's Table 5
  glm::vec3 base_color;
  float roughness;
  float metalness;
};

// Table 10: diffuse (0.5, 0.5, 0.5), R 1, M 0; matte silver (0.972, 0.960, 0.915), R 0.5,
// M 1; mirror silver, the same colour, R 0, M 1.
const std::array<SphereMaterial, 3>& sphere_materials();

struct RelightSettings {
  int size = 64;         // pixels (square)
  int spp = 32;
  int max_bounces = 2;   // a convex sphere: one bounce reaches the environment
  uint64_t seed = 1;
};

struct RelitSphere {
  Image color;  // size x size RGB linear
  Image mask;   // 1 on the sphere
};

// A UV sphere of `radius` at the origin (smooth outward normals, `segments` x `rings`) of
// `material` alone: the relighting sphere, and the insertion benchmark's objects.
scenes::Scene material_sphere(const SphereMaterial& material, float radius, int segments, int rings);

// Renders `material` lit by `probe` (an h x w equirect RGB image, linear radiance).
RelitSphere relight_sphere(const Image& probe, const SphereMaterial& material, const RelightSettings& settings);

}  // namespace phyir::eval
