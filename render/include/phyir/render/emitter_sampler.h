#pragma once
// Next-event estimation on emissive triangles: picks a triangle with probability
// proportional to its emitted power (area x luminance of the emission, times the mean of
// the emissive texture), then a uniform point on it. pdf() returns the solid-angle
// density of the same strategy, for multiple importance sampling when a BSDF-sampled ray
// hits an emitter. Empty when the scene has no emitters (then the integrator does no
// light sampling at all).
#include <glm/glm.hpp>

#include <vector>

#include "phyir/render/sampling.h"
#include "phyir/scenes/scene.h"

namespace phyir::render {

struct EmitterSample {
  glm::vec3 position{0.0f};
  glm::vec3 normal{0.0f};      // unit geometric normal of the emitter, as wound
  glm::vec3 wi{0.0f};          // unit direction from the reference point to the sample
  float distance = 0.0f;
  // Emitted toward the reference point: 0 if it sees the back of a one-sided emitter or
  // the point is cut out by alpha MASK (the accelerator lets rays through there).
  glm::vec3 radiance{0.0f};
  float pdf = 0.0f;            // solid angle, at the reference point
  int mesh = -1;
  int triangle = -1;
};

class EmitterSampler {
 public:
  explicit EmitterSampler(const scenes::Scene& scene);

  bool empty() const { return triangles_.empty(); }
  size_t emissive_triangle_count() const { return triangles_.size(); }
  float total_power() const { return distribution_.total(); }

  bool sample(const glm::vec3& reference, float u_select, const glm::vec2& u_point,
              EmitterSample* out) const;

  // Solid-angle pdf of having sampled `point` on (mesh, triangle) from `reference`:
  // pmf(triangle) / area * d^2 / |cos at the emitter|. Bit-identical to sample()'s pdf for
  // the same point. Zero for non-emissive triangles, and for grazing points
  // (|cos| < kMinCosine), which sample() rejects (returns false), keeping MIS consistent.
  float pdf(const glm::vec3& reference, int mesh, int triangle, const glm::vec3& point) const;

 private:
  struct EmissiveTriangle {
    int mesh, triangle;
    glm::vec3 p0, p1, p2;
    glm::vec3 normal;  // unit
    float area;
  };
  const scenes::Scene* scene_;
  std::vector<EmissiveTriangle> triangles_;
  // (mesh, triangle) -> index in triangles_: lookup_[first_of_mesh_[mesh] + triangle],
  // -1 for triangles that are never sampled (zero area, zero power). first_of_mesh_ is -1
  // for meshes without emitters.
  std::vector<int> first_of_mesh_;
  std::vector<int> lookup_;
  Distribution1D distribution_;
};

}  // namespace phyir::render
