#pragma once
// The cache's error at a probe's own surface, measured by the probe's front texels and taken
// out of the lookups of its texels behind (docs/probes-estimator.md, "The foot correction").
#include <vector>

#include <glm/glm.hpp>

#include "phyir/render/probe_grid.h"
#include "radiance_cache.h"

namespace phyir::render {

// Which texels of an h x w probe lie wholly behind a surface: each bounded by a cone round its
// centre direction through its farthest corner.
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
  // One texel: `radiance_cos`, `emitted_cos` its sample means of the radiance and of its part
  // emitted by a light seen first, times max(0, d . normal); `solid_angle` the texel's;
  // `variance_cos` the variance of radiance_cos's luminance.
  void add_texel(const glm::vec3& radiance_cos, const glm::vec3& emitted_cos, float solid_angle,
                 float variance_cos = 0.0f);
  float cosine(const glm::vec3& direction) const { return glm::max(glm::dot(direction, normal_), 0.0f); }
  glm::vec3 indirect() const { return glm::vec3(indirect_); }
  glm::vec3 direct() const { return glm::vec3(direct_); }
  // The variance of the measured irradiance's luminance (the texels' errors independent).
  float variance() const { return float(variance_); }

 private:
  glm::vec3 normal_;
  glm::dvec3 indirect_{0.0}, direct_{0.0};
  double variance_ = 0.0;
};

class FootCorrection {
 public:
  FootCorrection() = default;  // inactive: changes nothing

  // The difference between the probe's measurement and the cache at the foot; inactive without
  // a cell at the foot or beyond a factor 4 (the probe sees light the foot cannot).
  static FootCorrection measure(const RadianceCache& cache, const ProbeSite& site, const FootIrradiance& measured);
  // The mean difference of the active corrections (the last bounce, see above), 0 if none.
  static glm::vec3 common_difference(const std::vector<FootCorrection>& corrections);
  // The same correction less a difference common to every probe.
  FootCorrection less(const glm::vec3& common) const;

  // A lookup's block (CachedIrradiance::block) where its error is mostly the measurement's,
  // common to the probe's texels.
  static constexpr uint64_t kFootBlock = ~uint64_t(0);

  // Shifts a lookup at `position` (unit shading normal `normal`) by the correction's share w
  // there; the irradiance stays >= 0. Its variances become (1 - w)^2 the cache's plus w^2 the
  // measurement's; where w >= 1/2 its block becomes kFootBlock.
  void apply(const glm::vec3& position, const glm::vec3& normal, CachedIrradiance* E) const;

  bool active() const { return active_; }
  // Measured minus cached irradiance at the foot.
  const glm::vec3& difference() const { return difference_; }

 private:
  glm::vec3 foot_{0.0f}, normal_{0.0f, 1.0f, 0.0f};
  glm::vec3 difference_{0.0f};
  float variance_ = 0.0f;  // the measurement's
  float cell_ = 0.0f;
  bool has_direct_ = false;
  bool active_ = false;
};

}  // namespace phyir::render
