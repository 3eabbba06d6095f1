#include "foot_correction.h"

#include <algorithm>
#include <cmath>

#include "phyir/core/safe_math.h"

namespace phyir::render {

namespace {

// On the foot's surface: normal within ~25 degrees and within half a cell of its plane (a shelf
// 3 cm in front of a wall is another surface).
constexpr float kSameSurfaceCos = 0.9f;
constexpr float kPlaneCells = 0.5f;
// The correction holds in full within one cell of the foot and fades to none at three: the
// cache's error varies over the 3 x 3 cells its indirect light is smoothed over.
constexpr float kFullCells = 1.0f;
constexpr float kReachCells = 3.0f;
// A measurement more than this factor off the cache's value at the foot is not the same light.
constexpr float kMaxRatio = 4.0f;

}  // namespace

TexelCones::TexelCones(int height, int width) {
  cones_.reserve(size_t(height) * size_t(width));
  for (int row = 0; row < height; ++row)
    for (int col = 0; col < width; ++col) {
      // A texel's farthest point from its centre direction is one of its corners.
      const ProbeTexel texel(row, col, height, width);
      const glm::vec3 axis = texel.direction(glm::vec2(0.5f));
      float min_cos = 1.0f;
      for (int corner = 0; corner < 4; ++corner)
        min_cos = std::min(min_cos, glm::dot(axis, texel.direction(glm::vec2(float(corner & 1), float(corner >> 1)))));
      const float radius = std::acos(std::clamp(min_cos, -1.0f, 1.0f));
      cones_.push_back({axis, std::sin(std::min(radius + 1e-3f, 1.5707963f))});
    }
}

bool TexelCones::faces_away(int texel, const glm::vec3& normal) const {
  // The whole cone is below the plane iff its axis is at least 90 degrees + radius from the normal.
  const Cone& cone = cones_[size_t(texel)];
  return glm::dot(cone.axis, normal) < -cone.sin_radius;
}

void FootIrradiance::add_texel(const glm::vec3& radiance_cos, const glm::vec3& emitted_cos, float solid_angle,
                               float variance_cos) {
  direct_ += glm::dvec3(emitted_cos) * double(solid_angle);
  indirect_ += glm::dvec3(radiance_cos - emitted_cos) * double(solid_angle);
  variance_ += double(variance_cos) * double(solid_angle) * double(solid_angle);
}

FootCorrection FootCorrection::measure(const RadianceCache& cache, const ProbeSite& site, const FootIrradiance& measured) {
  FootCorrection out;
  CachedIrradiance E;
  if (!cache.interpolate(CachePoint{site.surface, site.normal, site.normal}, &E)) return out;
  // Both leave the punctual lights out: no texel holds them, and the cache keeps them apart.
  const glm::vec3 cached = E.has_direct ? E.indirect + E.direct : E.indirect;
  const glm::vec3 probe = E.has_direct ? measured.indirect() + measured.direct() : measured.indirect();
  const float cached_y = luminance(cached), probe_y = luminance(probe);
  if (!(cached_y > 0.0f) || !(probe_y >= cached_y / kMaxRatio && probe_y <= cached_y * kMaxRatio)) return out;
  out.foot_ = site.surface;
  out.normal_ = site.normal;
  out.difference_ = probe - cached;
  out.variance_ = measured.variance();
  out.cell_ = cache.settings().cell_size;
  out.has_direct_ = E.has_direct;
  out.active_ = true;
  return out;
}

glm::vec3 FootCorrection::common_difference(const std::vector<FootCorrection>& corrections) {
  glm::dvec3 sum(0.0);
  size_t count = 0;
  for (const FootCorrection& c : corrections) {
    if (!c.active_) continue;
    sum += glm::dvec3(c.difference_);
    ++count;
  }
  return count > 0 ? glm::vec3(sum / double(count)) : glm::vec3(0.0f);
}

FootCorrection FootCorrection::less(const glm::vec3& common) const {
  FootCorrection out = *this;
  out.difference_ -= common;
  return out;
}

void FootCorrection::apply(const glm::vec3& position, const glm::vec3& normal, CachedIrradiance* E) const {
  if (!active_ || E->has_direct != has_direct_ || glm::dot(normal, normal_) < kSameSurfaceCos) return;
  const glm::vec3 d = position - foot_;
  const float height = glm::dot(d, normal_);
  if (std::abs(height) > kPlaneCells * cell_) return;
  const float across = glm::length(d - height * normal_);
  const float w = std::clamp((kReachCells * cell_ - across) / ((kReachCells - kFullCells) * cell_), 0.0f, 1.0f);
  if (!(w > 0.0f)) return;
  // The shift goes to the indirect part; what it takes below zero comes off the direct part.
  const glm::vec3 indirect = E->indirect + w * difference_;
  E->indirect = glm::max(indirect, glm::vec3(0.0f));
  if (has_direct_) E->direct = glm::max(E->direct + glm::min(indirect, glm::vec3(0.0f)), glm::vec3(0.0f));
  // The cache's error at the foot cancels in the share w; the measurement's takes its place.
  const float kept = (1.0f - w) * (1.0f - w);
  E->indirect_variance = kept * E->indirect_variance + w * w * variance_;
  E->direct_variance *= kept;
  if (w >= 0.5f) E->block = kFootBlock;
}

}  // namespace phyir::render
