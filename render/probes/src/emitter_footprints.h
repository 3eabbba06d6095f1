#pragma once
// The texels of a probe in which a light may appear, found before any sample (stratified
// samples can miss a sliver of light); docs/probes-estimator.md, "Lights seen directly".
#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

#include "phyir/render/light_triangles.h"
#include "phyir/scenes/scene.h"

namespace phyir::render {

class EmitterFootprints {
 public:
  explicit EmitterFootprints(const scenes::Scene& scene);

  static constexpr uint8_t kCovered = 1;  // a light may cover the texel
  static constexpr uint8_t kEdge = 2;     // ... and a light's outline may cross it

  // Raises flags[row * w + col] of an h x w probe at `origin` to kCovered where a front-facing
  // emissive triangle may cover the texel, occlusion ignored, and to kEdge where a light's
  // outline may cross it (what counts as outline, and the clusters: docs/probes-estimator.md,
  // "Lights seen directly: exact coverage").
  void mark(const glm::vec3& origin, int h, int w, std::vector<uint8_t>* flags) const;

 private:
  struct Triangle : LightTriangle {
    bool outline[3];  // edge p[e] -> p[e+1] may be on the light's outline (not coplanar with a neighbour)
    int across[3];    // the triangle of its mesh across that edge where the edge is a crease, else -1
  };
  // Sets outline and across once the triangles are in their final order.
  void find_outlines();
  // Up to kClusterSize triangles of one mesh, close together: triangles_[first, first + count).
  struct Cluster {
    glm::vec3 center{0.0f};
    float radius = 0.0f;  // of a sphere holding every vertex
    uint32_t first = 0, count = 0;
    bool whole_light = false;  // all the light triangles of its mesh (at most kClusterSize)
  };
  static constexpr uint32_t kClusterSize = 32;  // lights this small go per triangle: as cheap, tighter
  // Sorts triangles_ into clusters (median splits along the longest axis, per mesh).
  void build_clusters();
  // Marks the cluster's bounding-sphere cap (kEdge) if under a texel; else false, marks nothing.
  bool mark_small_cluster(const Cluster& c, const glm::vec3& origin, int h, int w, std::vector<uint8_t>* flags) const;
  // The two steps of marking a triangle: the texel box (kCovered), the outline's texels (kEdge).
  void mark_box(const Triangle& tri, const glm::vec3& origin, int h, int w, std::vector<uint8_t>* flags) const;
  void mark_outline(const Triangle& tri, const glm::vec3& origin, int h, int w, std::vector<uint8_t>* flags) const;
  // Whether the ray from `o` along `d` crosses the triangle (Moller-Trumbore).
  static bool surrounds(const Triangle& t, const glm::vec3& o, const glm::vec3& d);
  std::vector<Triangle> triangles_;
  std::vector<Cluster> clusters_;
};

}  // namespace phyir::render
