#pragma once
// The emissive triangles of a scene, to find the texels of a light probe in which a light
// can appear before any sample is taken: those texels are the ones whose partial coverage
// of a very bright surface dominates a probe's error, and a few stratified samples can miss
// a sliver of light entirely (a ceiling panel seen edge-on from a probe on the ceiling).
// Used by the probe renderer's cache mode (probe_renderer.h, docs/probes.md).
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
  // edges no other emissive triangle of its mesh shares, sampled at 1/8 of a texel) falls
  // in are raised to kEdge: there coverage is partial.
  void mark(const glm::vec3& origin, int h, int w, std::vector<uint8_t>* flags) const;

 private:
  struct Triangle : LightTriangle {
    bool outline[3];  // edge p[e] -> p[e+1] is on the light's outline (not shared in its mesh)
  };
  // The two steps of mark(): the texel box (kCovered), the outline's texels (kEdge).
  void mark_box(const Triangle& tri, const glm::vec3& origin, int h, int w, std::vector<uint8_t>* flags) const;
  void mark_outline(const Triangle& tri, const glm::vec3& origin, int h, int w, std::vector<uint8_t>* flags) const;
  // Whether the ray from `o` along `d` crosses the triangle (Moller-Trumbore).
  static bool surrounds(const Triangle& t, const glm::vec3& o, const glm::vec3& d);
  std::vector<Triangle> triangles_;
};

}  // namespace phyir::render
