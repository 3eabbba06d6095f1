#pragma once
// Light portals: the openings (windows) through which the environment lights an interior,
// sampled so that directions towards the sky go where the sky can be seen
// (docs/gltf-support.md#light-portals; as Cycles' portal lights and Mitsuba's and Arnold's
// equivalents).
//
// From a point x inside, a direction is drawn uniformly over the solid angle the portals
// facing x cover: a portal (two triangles) is chosen by its solid angle, then a direction
// uniformly inside it (Arvo's spherical triangles, spherical_triangle.h). Its density is
// (portals the direction passes through) / (their total solid angle), so overlapping portals
// stay exact. It says nothing about the environment's brightness: next-event estimation
// chooses it or the environment's own density per sample and weights both against the
// BRDF's by multiple importance sampling (direct_lighting.h); every strategy keeps its
// weight, so a portal missing from the list only costs noise, never light.
#include <vector>

#include <glm/glm.hpp>

#include "phyir/scenes/scene.h"

namespace phyir::render {

class EnvironmentPortals {
 public:
  EnvironmentPortals() = default;
  explicit EnvironmentPortals(const std::vector<scenes::Portal>& portals);

  bool empty() const { return portals_.empty(); }
  size_t size() const { return portals_.size(); }

  // A direction from x through a portal that faces x, uniform in solid angle (u: three
  // uniforms, the last choosing the triangle), and its density; false where none faces x.
  bool sample(const glm::vec3& x, const glm::vec3& u, glm::vec3* direction, float* density) const;
  // The density sample() gives `direction` from x (0 outside every portal).
  float pdf(const glm::vec3& x, const glm::vec3& direction) const;

 private:
  struct Quad {
    glm::vec3 corner, edge_u, edge_v, inward;  // inward: unit normal towards the interior
  };
  bool faces(const Quad& q, const glm::vec3& x) const;
  bool passes_through(const Quad& q, const glm::vec3& x, const glm::vec3& direction) const;
  // The portals' total solid angle from x.
  double solid_angle(const glm::vec3& x) const;
  // The triangle (quad, which of its two) whose share of the portals' solid angle from x
  // holds `target` (in [0, total)), walking the portals in order without keeping a list.
  bool pick_triangle(const glm::vec3& x, double target, const Quad** quad, int* which) const;

  std::vector<Quad> portals_;
};

}  // namespace phyir::render
