#pragma once
// The cache's error at a probe's own surface, measured by the probe and taken out
// (docs/probes-estimator.md, "The foot correction").
//
// Why. The texels of a probe that look back at the surface it sits on see it within a few
// centimetres of the probe's foot, so they all read the same one or two cache cells, and
// share those cells' fill noise: it does not average out over texels the way per-direction
// noise does. Measured on the bench: those texels were off by up to 4-6% as a block, and
// 1024 instead of 128 estimates per cell brought that to about 1%.
//
// How. The probe measures the light reaching its foot itself: its front hemisphere
// integrated against the cosine is the irradiance there, from hundreds of texels whose
// errors are independent. So the texels that face away from the front are shaded last,
// with the cache's irradiance near the foot shifted by the difference between that
// measurement and the cache's own value at the foot: in full within one cell of the foot,
// fading to none at three, on the foot's surface only (same normal, within half a cell of
// its plane). Indirect light is compared with indirect light (emission seen first is direct
// light); where the cache holds the direct light too, totals are compared.
//
// One difference is not the cache's error. The light the probe measures has scattered up
// to max_bounces times, the cache's up to max_bounces - 1 (so that a lookup at a probe
// ray's hit gives the path tracer's path lengths): the probe also sees the last bounce,
// about 2% of the light in the mini room. That bounce has scattered so often that it is
// nearly the same all over a room, so the mean difference over the view's probes estimates
// it, and each probe's correction is its own difference less that mean.
#include <vector>

#include <glm/glm.hpp>

#include "phyir/render/probe_grid.h"
#include "radiance_cache.h"

namespace phyir::render {

// Which texels of an h x w probe lie wholly behind a surface of a given normal. Each texel is
// bounded by a cone round its centre direction (through its farthest corner), computed once.
class TexelCones {
 public:
  TexelCones(int height, int width);
  // Every direction of texel t points below the plane of `normal` (d . normal < 0).
  bool faces_away(int texel, const glm::vec3& normal) const;

 private:
  struct Cone {
    glm::vec3 axis;
    float sin_radius;
  };
  std::vector<Cone> cones_;
};

// The probe's measurement: sum over directions of radiance x max(0, cos) x weight.
class FootIrradiance {
 public:
  explicit FootIrradiance(const glm::vec3& normal) : normal_(normal) {}
  // One texel's estimate: `radiance_cos` and `emitted_cos` are its sample means of the
  // radiance (and of its part emitted by a light seen first) times max(0, d . normal);
  // `solid_angle` is the texel's.
  void add_texel(const glm::vec3& radiance_cos, const glm::vec3& emitted_cos, float solid_angle);
  float cosine(const glm::vec3& direction) const { return glm::max(glm::dot(direction, normal_), 0.0f); }
  glm::vec3 indirect() const { return glm::vec3(indirect_); }
  glm::vec3 direct() const { return glm::vec3(direct_); }

 private:
  glm::vec3 normal_;
  glm::dvec3 indirect_{0.0}, direct_{0.0};
};

class FootCorrection {
 public:
  FootCorrection() = default;  // inactive: changes nothing

  // The difference between the probe's measurement and the cache at the foot; inactive where
  // the cache has no cell at the foot, or where the two differ by more than a factor 4 (then
  // they do not measure the same light: the probe sees something the foot cannot).
  static FootCorrection measure(const RadianceCache& cache, const ProbeSite& site, const FootIrradiance& measured);
  // The mean difference of the active corrections (the last bounce, see above), 0 if none.
  static glm::vec3 common_difference(const std::vector<FootCorrection>& corrections);
  // The same correction less a difference common to every probe.
  FootCorrection less(const glm::vec3& common) const;

  // Shifts a lookup at `position` (unit shading normal `normal`) by the correction's share
  // there; the irradiance stays >= 0.
  void apply(const glm::vec3& position, const glm::vec3& normal, CachedIrradiance* E) const;

  bool active() const { return active_; }
  // Measured minus cached irradiance at the foot.
  const glm::vec3& difference() const { return difference_; }

 private:
  glm::vec3 foot_{0.0f}, normal_{0.0f, 1.0f, 0.0f};
  glm::vec3 difference_{0.0f};
  float cell_ = 0.0f;
  bool has_direct_ = false;
  bool active_ = false;
};

}  // namespace phyir::render
