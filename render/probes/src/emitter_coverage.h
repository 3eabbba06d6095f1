#pragma once
// How much of a probe texel each light covers, exactly and occlusion ignored, and where:
// visible_emission's directions then estimate only what an occluder hides (partial coverage,
// converging as N^-3/4, is a stratified texel's largest error). Exact: (phi, cos theta) is an
// equal-area map, a texel a rectangle in it; docs/probes-estimator.md, "Lights seen directly".
#include <glm/glm.hpp>

#include <vector>

#include "phyir/render/light_triangles.h"
#include "phyir/scenes/scene.h"

namespace phyir::render {

class EmitterCoverage {
 public:
  explicit EmitterCoverage(const scenes::Scene& scene);

  // False (texels keep the plain estimate) with no lights, a textured light or > 4096 light triangles.
  bool usable() const { return usable_; }

  // The lights as seen from one probe origin.
  class View {
   public:
    // False when an arc passes too close to a pole to trace (texels keep the plain estimate).
    bool valid() const { return valid_; }
    // Mean over texel (row, col) of an h x w probe of the emission arriving with no occluder.
    glm::vec3 texel_mean(int row, int col, int h, int w) const;
    // One light triangle's part of a texel, occlusion ignored.
    struct Piece {
      int light = 0;                  // which triangle (for hits())
      glm::vec3 emission{0.0f};
      double fraction = 0.0;          // of the texel's solid angle it covers
      glm::dvec2 lo{0.0}, hi{0.0};    // bounding box of that part in (phi unwrapped, cos theta)
    };
    // The parts of texel (row, col) of an h x w probe that lights cover (fraction > 0).
    void texel_pieces(int row, int col, int h, int w, std::vector<Piece>* pieces) const;
    // Whether unit d points into triangle `light`; if so *distance is how far along d its plane is.
    bool hits(int light, const glm::vec3& d, float* distance) const;

   private:
    friend class EmitterCoverage;
    struct Seen {
      glm::vec3 edge_normal[3];            // inside: d . edge_normal[e] >= 0 for all e
      glm::vec3 to_plane, plane_normal;    // a vertex relative to the origin; the unit normal
      glm::vec3 emission;
      std::vector<glm::dvec2> outline;     // (phi unwrapped, cos theta), closed
      double phi_min = 0.0, phi_max = 0.0;
      double z_min = 0.0, z_max = 0.0;
    };
    bool inside(const Seen& s, const glm::vec3& d) const {
      return glm::dot(d, s.edge_normal[0]) >= 0.0f && glm::dot(d, s.edge_normal[1]) >= 0.0f &&
             glm::dot(d, s.edge_normal[2]) >= 0.0f;
    }
    std::vector<Seen> seen_;
    bool valid_ = true;
  };
  View view(const glm::vec3& origin) const;

 private:
  std::vector<LightTriangle> triangles_;
  bool usable_ = false;
};

}  // namespace phyir::render
