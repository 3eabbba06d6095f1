#pragma once
// Light subpaths from the point and spot lights, one surface vertex long, joined to the
// vertices of a path: the bidirectional strategy that samples the light a bulb sends to the
// surfaces a few centimetres from it from the bulb's side (Veach 1997, ch. 10: the strategy
// s = 2 of bidirectional path tracing; docs/light-subpaths.md).
//
// A path vertex x sees the light a punctual light l reflects off a surface point y:
//   integral over y of f_x(wo, x->y) L1(y->x) G(x, y) V(x, y) dA(y),
//   L1(y->x) = f_y(y->x, y->l) E_l(y) cos_y,l        (E_l: l's irradiance facing it)
// The path tracer's own strategy (the eye strategy) draws y by sampling x's BRDF and adds
// l's next-event estimate at y: its density of y (area measure) is
//   p_eye(y) = p_x(x->y) cos_y / |x - y|^2 * P_nee(l | y),
// where P_nee is the probability that y's next-event estimate chooses l. Near a bulb E_l
// grows as 1 / r^2 over a patch that x's rays hit rarely: the eye strategy's estimates are
// heavy-tailed (a handful of paths carry most of the light). The light strategy draws y
// by choosing light l with probability P(l | x0) (its power over its squared distance to the
// path's first joining vertex x0)
// and a direction from it (uniform over a point light's sphere or a spot's outer cone,
// density p_l(w)), traced to its first hit: density
//   p_light(y) = P(l | x0) p_l(l->y) cos_y,l / r^2,
// and joined to x by one shadow ray. Both are weighted by the power heuristic over
// (p_eye, p_light), which sums to one for every y, so the sum is unbiased; near the bulb
// p_light is large and takes the light with bounded estimates (1 / r^2 cancels), far from
// it the eye strategy keeps it. Transmittance through blended surfaces is in neither
// density: the light subpath passes them stochastically, as the eye's shadow ray weighs them.
//
// Where y cannot be joined (a mirror, glass, the light below its plane as seen from x) the
// light strategy's density is 0 and the eye strategy's weight 1; directional lights have no
// light strategy. A path draws one light subpath, at its first joining vertex, and joins it
// at every vertex (as bidirectional path tracing joins one light subpath to every eye
// vertex): one ray per path and one shadow ray per joined vertex.
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "phyir/render/direct_lighting.h"
#include "phyir/render/guide_mixture.h"
#include "phyir/render/interaction.h"
#include "phyir/render/path_counters.h"
#include "phyir/render/render_scene.h"

namespace phyir::render {

// A light subpath: the light, where it was chosen from, and the surface its direction
// found first.
struct LightVertex {
  int light = -1;
  glm::vec3 choice_from{0.0f};  // the vertex whose P(l | x) chose the light
  SurfaceInteraction hit;       // normals face the light
  // What every join of it weighs with, the same at each: the light strategy's density of
  // `hit` and the probability that a next-event estimate there chooses `light`.
  float density = 0.0f;
  float nee_pmf = 0.0f;
};

// The random numbers of one light subpath.
struct LightSubpathVariates {
  float choice = 0.5f;     // which light
  glm::vec2 direction{0.5f};
};

class LightSubpaths {
 public:
  LightSubpaths() = default;  // none
  explicit LightSubpaths(const RenderScene& scene);

  // No point or spot light: nothing to join.
  bool empty() const { return lights_.empty(); }

  // One light subpath, its light chosen from `choice_from` (one ray, counted); false where
  // it leaves the scene or lands where it cannot be joined (joinable()).
  bool sample(const glm::vec3& choice_from, const LightSubpathVariates& u, LightVertex* out,
              PathCounters* counters) const;

  // The light strategy's density (area measure) of a joinable point y, geometric normal
  // `ng_y` facing the joining vertex, for light `light` (a DeltaLights index) chosen from
  // `choice_from`; 0 where the light is behind y's plane, outside a spot's cone, or
  // directional.
  float density(const glm::vec3& choice_from, int light, const glm::vec3& y, const glm::vec3& ng_y) const;

  // The power-heuristic weight of the eye strategy's next-event estimate at y of punctual
  // light `light`, chosen there with probability `nee_pmf`, on a path that came from
  // `previous`; y must not be glass (the caller's check: ShadingPoint does not know).
  float eye_weight(const PreviousVertex& previous, const ShadingPoint& y, int light, float nee_pmf) const;

  // Subpath `v` joined to x (its lobes `lobes`; the eye's ray from x is drawn from `guide`'s
  // mixture of them), MIS-weighted, times `throughput`. One shadow ray, counted.
  glm::vec3 join(const ShadingPoint& x, const LightVertex& v, Lobes lobes, const GuideMixture& guide,
                 const glm::vec3& throughput, PathCounters* counters) const;

  // Whether a light subpath can end at this surface: neither a mirror nor glass.
  static bool joinable(const SurfaceInteraction& y);

 private:
  struct Light {
    int index = -1;  // in the scene's DeltaLights
    glm::vec3 position{0.0f};
    glm::vec3 axis{0.0f, 0.0f, -1.0f};  // a spot's
    float cos_outer = -1.0f;            // -1: the whole sphere
    float power = 0.0f;                 // luminance, W
  };
  // The choice weight of entry k of lights_ from x (power over squared distance; power alone
  // beyond kMaxSpatialLights lights).
  float choice_weight(const glm::vec3& x, size_t k) const;
  // P(l | x) for entry k of lights_.
  float choice_pmf(const glm::vec3& x, int k) const;
  int entry_of(int light) const;
  // The eye strategy's density of the subpath's hit from x (drawn from `guide`'s mixture).
  static float eye_density(const ShadingPoint& x, Lobes lobes, const GuideMixture& guide, const glm::vec3& wi_world,
                           const LightVertex& v, float distance2);

  const RenderScene* scene_ = nullptr;
  std::vector<Light> lights_;
  std::vector<int> entry_;  // DeltaLights index -> index in lights_, -1 for directional
  float total_power_ = 0.0f;
};

}  // namespace phyir::render
