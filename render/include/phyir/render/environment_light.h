#pragma once
// An HDR equirectangular environment (windows, sky, or a light probe when relighting),
// in the toolkit's equirect mapping (equirect.h). Radiance is piecewise constant per
// texel, so sample() and pdf() are exact: texels are picked proportionally to
// luminance x solid angle (one alias-table draw over every texel: one memory read, where a
// row-then-column search missed the cache at each step), then a direction uniformly inside
// the texel's solid angle.
#include <glm/glm.hpp>

#include <memory>
#include <vector>

#include "phyir/core/image.h"
#include "phyir/render/alias_table.h"

namespace phyir::render {

// Light from outside the scene that depends on where it arrives, not only from where (object
// insertion: the probes nearest the path vertex). The environment's own texels still choose
// the sampled directions; this only says what radiance arrives along them.
class PositionalRadiance {
 public:
  virtual ~PositionalRadiance() = default;
  virtual glm::vec3 radiance(const glm::vec3& position, const glm::vec3& direction) const = 0;
};

class EnvironmentLight {
 public:
  // `image`: linear RGB(A), any size >= 1x1. `scale` multiplies the radiance.
  EnvironmentLight(const Image& image, float scale = 1.0f);

  glm::vec3 radiance(const glm::vec3& direction) const;
  // With a positional source set, the radiance arriving at `position` from `direction` is
  // the source's, else radiance(direction); sampling keeps this map's density.
  void set_positional(std::shared_ptr<const PositionalRadiance> source) { positional_ = std::move(source); }
  bool positional() const { return positional_ != nullptr; }
  glm::vec3 radiance_at(const glm::vec3& position, const glm::vec3& direction) const {
    return positional_ ? positional_->radiance(position, direction) : radiance(direction);
  }
  // Three uniforms: the texel (u.x, u.y: alias_table.h), then the direction inside it (u.y
  // remapped, u.z). Returns false if the environment is black everywhere.
  bool sample(const glm::vec3& u, glm::vec3* direction, glm::vec3* radiance, float* pdf) const;
  float pdf(const glm::vec3& direction) const;
  // Starts loading what sample(u) reads first (its alias bin and that bin's own texel): with
  // a sky of 2^19 texels both are cache misses, which a caller hides by asking for them
  // before it traces a ray and sampling after.
  void prefetch(const glm::vec3& u) const;
  int width() const { return width_; }
  int height() const { return height_; }

 private:
  int width_ = 0, height_ = 0;
  std::vector<glm::vec3> texels_;
  AliasTable choice_;                 // over texels, row-major
  std::vector<double> cos_edges_;     // cos(theta) at the top of each row, and the bottom's
  std::vector<float> solid_angles_;   // of a texel, per row
  std::shared_ptr<const PositionalRadiance> positional_;
};

}  // namespace phyir::render
