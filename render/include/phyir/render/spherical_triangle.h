#pragma once
// A triangle as seen from a point: the region of the sphere of directions it covers, its
// solid angle and uniform sampling over it (Arvo, "Stratified Sampling of Spherical
// Triangles", SIGGRAPH 1995). Light sampling uses it for emitters that are large or near
// (emitter_sampler.h): a uniform point on the triangle's area puts most samples where the
// light is far, and a thin strip light seen from beside it (the edge of a ceiling fixture,
// from the ceiling) becomes a heavy-tailed estimate; uniform in solid angle it is not.
// Double precision: the angle sum loses ~1e-16 / solid angle to cancellation.
#include <glm/glm.hpp>

namespace phyir::render {

class SphericalTriangle {
 public:
  // False when the triangle has no solid angle from `reference` (seen edge-on, or
  // `reference` on it) or a vertex coincides with it.
  bool set(const glm::vec3& reference, const glm::vec3& p0, const glm::vec3& p1, const glm::vec3& p2);

  double solid_angle() const { return solid_angle_; }
  // A unit direction, uniform in solid angle over the triangle for u uniform on [0,1)^2;
  // the map is continuous and measure-preserving, so stratified u stay stratified.
  glm::vec3 sample(const glm::vec2& u) const;

 private:
  glm::dvec3 a_{0.0}, b_{0.0}, c_{0.0};  // unit directions to the vertices
  double alpha_ = 0.0;                    // the interior angle at a
  double solid_angle_ = 0.0;
};

}  // namespace phyir::render
