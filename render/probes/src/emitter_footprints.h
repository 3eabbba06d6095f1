#pragma once
// The emissive triangles of a scene, to find the texels of a light probe in which a light
// can appear before any sample is taken: those texels are the ones whose partial coverage
// of a very bright surface dominates a probe's error, and a few stratified samples can miss
// a sliver of light entirely (a ceiling panel seen edge-on from a probe on the ceiling).
// Used by the probe renderer's cache mode (probe_renderer.h, docs/probes-estimator.md).
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

  // Raises flags[row * w + col] to kCovered for every texel of an h x w probe at `origin`
  // that a front-facing emissive triangle may cover, occlusion ignored: the texel box of
  // points sampled densely along its edges, grown by one texel, or the whole cap when the
  // triangle surrounds a pole. Texels that a point of the light's outline (the triangle
  // edges not shared with a coplanar emissive triangle of its mesh, sampled at 1/8 of a texel) falls
  // in are raised to kEdge: there coverage is partial. A crease between two triangles of one
  // light (edges matched by position, sides wound consistently) is on its outline only where
  // `origin` sees one side from the front and the other from behind: from inside an emitting
  // box, or in front of two faces of a box light, the light continues across it. A cluster of nearby light triangles
  // (a lamp shade of real furniture has thousands) that subtends less than a texel is marked
  // as the cap of its bounding sphere, all kEdge: a per-probe cost in clusters, not triangles.
  // A light of at most 32 triangles (a panel, a box) is marked triangle by triangle: as cheap,
  // and tighter.
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
  static constexpr uint32_t kClusterSize = 32;
  // Sorts triangles_ into clusters (median splits along the longest axis, per mesh).
  void build_clusters();
  // Marks the cap of the cluster's bounding sphere (kEdge) when it is smaller than a texel
  // seen from `origin`; false (nothing marked) when it is not.
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
