#pragma once
// Next-event estimation on emissive triangles, in two steps:
//  1. a cluster of emissive triangles (the coplanar triangles of one mesh, e.g. one face
//     of a light panel, or a whole curved mesh such as a bulb) is picked with probability
//     proportional to power x (an upper bound of the cosine at the emitter, for planar
//     clusters) / distance^2 from the reference point; zero when a one-sided planar
//     cluster faces away from it (it cannot light the point);
//  2. a triangle of that cluster by power (area x luminance of the emission x mean of the
//     emissive texture); within the cluster's own size of its bounds (its diagonal), half of
//     the samples by power and half by descending the cluster's tree (emitter_tree.h), which
//     favours the triangles nearest the reference point, with the mixture's pmf, so a
//     triangle is never picked at under half its power share (the tree's bound can be loose
//     inside a curved lamp). Farther away the tree would choose nearly by power anyway, and
//     its descent costs (a third more time on the night apartment's probes when every
//     sample took it). Then a point on the triangle: uniform in solid angle
//     (spherical_triangle.h) where the triangle is long for its distance (its longest edge
//     more than kSolidAngleExtent x the distance to its centroid: a strip light seen from
//     beside it, a panel from under it), where a uniform point on its area would leave the
//     estimate dominated by the rare samples on its nearest part; uniform on its area
//     elsewhere (cheaper, and there 1 / distance^2 hardly varies over it).
// Step 1 is what keeps a ceiling lit by a lamp from wasting its samples on down-facing
// panels. The scene's punctual lights (delta_lights.h) take part in step 1 as clusters of
// their own, weighted by the irradiance they give the reference point (I x falloff / d^2,
// or E for a directional light): the same unit as the clusters' weights. Scenes with more
// than kMaxSpatialClusters clusters and punctual lights fall back to pure power selection
// (emissive triangles by pi x area x radiance, punctual lights by DeltaLights::power), which
// keeps the per-sample cost bounded.
// pdf() returns the solid-angle density of the same strategy for multiple importance
// sampling (of emissive triangles: a punctual light cannot be hit). Empty when the scene has
// no emitters and no punctual lights (the integrator then does no light
// sampling at all). Given the scene's accelerator, triangles that emit only into closed
// geometry (emitter_visibility.h) are left out: never sampled, pdf 0.
#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

#include "phyir/render/accelerator.h"
#include "phyir/render/delta_lights.h"
#include "phyir/render/emitter_tree.h"
#include "phyir/render/sampling.h"
#include "phyir/scenes/scene.h"

namespace phyir::render {

struct EmitterSample {
  glm::vec3 position{0.0f};
  glm::vec3 normal{0.0f};      // unit geometric normal of the emitter, as wound
  glm::vec3 wi{0.0f};          // unit direction from the reference point to the sample
  float distance = 0.0f;       // +infinity for a directional light
  // Emitted toward the reference point: 0 if it sees the back of a one-sided emitter or
  // the point is cut out by alpha MASK (the accelerator lets rays through there).
  // For a punctual light: the irradiance it gives a surface facing it.
  glm::vec3 radiance{0.0f};
  float pdf = 0.0f;            // solid angle, at the reference point; for a punctual light
                               // the probability of having chosen it
  int mesh = -1;               // -1 for a punctual light
  int triangle = -1;
  int light = -1;              // a punctual light's index in DeltaLights
  bool delta = false;          // a punctual light: no MIS, no surface at `position`
};

class EmitterSampler {
 public:
  static constexpr int kMaxSpatialClusters = 64;
  static constexpr float kSolidAngleExtent = 0.5f;

  explicit EmitterSampler(const scenes::Scene& scene, const Accelerator* occluders = nullptr);

  // No lights at all: neither emissive triangles nor punctual lights.
  bool empty() const { return triangles_.empty() && delta_.empty(); }
  const DeltaLights& delta_lights() const { return delta_; }
  size_t emissive_triangle_count() const { return triangles_.size(); }
  // Emissive triangles left out because they light only the inside of closed geometry.
  size_t enclosed_triangle_count() const { return enclosed_; }
  // Coincident copies of a double-sided emissive triangle (EmitterTwins, light_triangles.h), left
  // out: light sampling picks the sheet once, and a ray hitting a copy gets the kept one's pdf.
  size_t twin_triangle_count() const { return twins_; }
  size_t cluster_count() const { return clusters_.size(); }
  // More than kMaxSpatialClusters clusters and punctual lights: chosen by power alone, without trees.
  bool chosen_by_power() const { return !empty() && !spatial_; }
  float total_power() const { return distribution_.total(); }

  // A lower bound of the distance from `point` to every emitter that is ever sampled (the
  // nearest cluster's bounding box, or point or spot light); +infinity when there are none
  // (directional lights are infinitely far). Cost: one box test per cluster and light.
  float distance_bound(const glm::vec3& point) const;

  // punctual = false: the punctual lights are never chosen, every sample goes to the
  // emissive triangles (for callers that add the punctual lights exactly); pdf() must then
  // be asked the same.
  bool sample(const glm::vec3& reference, float u_select, const glm::vec2& u_point, EmitterSample* out,
              bool punctual = true) const;

  // Solid-angle pdf of having sampled `point` on (mesh, triangle) from `reference`:
  // pmf(triangle) / area * d^2 / |cos at the emitter|. Bit-identical to sample()'s pdf for
  // the same point. Zero for non-emissive triangles, and for grazing points
  // (|cos| < kMinCosine) and triangles in whose plane `reference` lies (seen edge-on: a point
  // on the light itself), which sample() rejects (returns false), keeping MIS consistent.
  float pdf(const glm::vec3& reference, int mesh, int triangle, const glm::vec3& point, bool punctual = true) const;
  // The probability that sample() (punctual = true) chooses punctual light `light` from
  // `reference`: its EmitterSample::pdf, without drawing one.
  float delta_pmf(const glm::vec3& reference, int light) const;

 private:
  struct EmissiveTriangle {
    int mesh, triangle;
    glm::vec3 p0, p1, p2;
    glm::vec3 normal;  // unit
    float area;
    glm::vec3 centroid;
    float longest_edge2;   // squared
    int cluster;           // index in clusters_
    int slot;              // index in its cluster's `triangles` (and tree)
    float pmf_in_cluster;  // its power share of the cluster
  };
  struct Cluster {
    std::vector<int> triangles;  // indices in triangles_
    Distribution1D distribution; // over `triangles`, by power
    EmitterTree tree;            // over `triangles`, by a bound of the irradiance at the point
    glm::vec3 centre{0.0f};
    glm::vec3 bounds_min{0.0f}, bounds_max{0.0f};
    float half_diagonal2 = 0.0f; // (half the bounding-box diagonal)^2
    float power = 0.0f;
    bool planar = false;           // all triangles in one plane
    bool one_sided_plane = false;  // planar, emitting from the front only
    glm::vec3 normal{0.0f};
    float plane_offset = 0.0f;     // dot(normal, point on the plane)
  };
  // Triangle t of mesh m with its area, normal and bounds; false when it has no area.
  static bool make_triangle(const scenes::Mesh& mesh, int m, int t, EmissiveTriangle* e);
  void build_clusters(const std::vector<float>& weights);
  // Selection weights seen from `reference` of every cluster, then of every punctual light;
  // returns their sum, and the clusters' alone in *triangle_total.
  float selection_weights(const glm::vec3& reference, float* weights, float* triangle_total) const;
  // The same, computed once per point and kept per thread: a shading point asks for them at
  // each of its light samples (8 near a light in the probes) and again for the MIS weight of
  // its BRDF ray. Valid until this thread's next call.
  // *total is the sum over the entries a choice with or without the punctual lights sees.
  const float* selection_weights_at(const glm::vec3& reference, bool punctual, float* total) const;
  // The spatial choice of a cluster or punctual light: its index in selection_weights' order.
  bool choose_spatially(const glm::vec3& reference, float u_select, bool punctual, int* entry, float* entry_pmf,
                        float* remapped) const;
  // The power-only choice between the triangles (as a whole) and each punctual light: false
  // when a punctual light was chosen (*light, *pmf); true for the triangles, with u_select
  // remapped to choose among them.
  bool chooses_triangles(float* u_select, int* light, float* pmf) const;
  bool sample_delta(int light, float pmf, const glm::vec3& reference, EmitterSample* out) const;
  float selection_pmf(const glm::vec3& reference, int index, bool punctual) const;
  // Whether step 2 uses the cluster's tree at `reference` (within the cluster's diagonal of its bounds).
  static bool near_cluster(const Cluster& c, const glm::vec3& reference);
  // The probability of step 2 choosing `e` once its cluster is chosen.
  float in_cluster_pmf(const glm::vec3& reference, const EmissiveTriangle& e) const;
  // Step 2: a triangle (index into triangles_) and in *pmf its in_cluster_pmf; -1 if none.
  int choose_in_cluster(const Cluster& c, const glm::vec3& reference, float u, float* pmf) const;
  // Whether points on `e` are sampled uniformly in solid angle from `reference` (step 2).
  static bool by_solid_angle(const EmissiveTriangle& e, const glm::vec3& reference);
  static glm::vec2 barycentrics_of(const EmissiveTriangle& e, const glm::vec3& point);
  const scenes::Scene* scene_;
  std::vector<EmissiveTriangle> triangles_;
  // (mesh, triangle) -> index in triangles_: lookup_[first_of_mesh_[mesh] + triangle],
  // -1 for triangles that are never sampled (zero area, zero power); a left-out twin maps to
  // the triangle kept in its place. first_of_mesh_ is -1
  // for meshes without emitters.
  std::vector<int> first_of_mesh_;
  std::vector<int> lookup_;
  Distribution1D distribution_;  // by power over all triangles (fallback selection)
  std::vector<Cluster> clusters_;
  DeltaLights delta_;
  Distribution1D delta_distribution_;  // by power over the punctual lights (fallback selection)
  float triangle_share_ = 1.0f;        // fallback selection: probability of the triangles
  bool spatial_ = false;               // clusters and punctual lights chosen by selection_weights
  size_t enclosed_ = 0;
  size_t twins_ = 0;
  uint64_t id_;  // tells this sampler's weights from another's in the per-thread memo
};

}  // namespace phyir::render
