#pragma once
// An HDR equirectangular environment (windows, sky, or a light probe when relighting),
// in the toolkit's equirect mapping (equirect.h). Radiance is piecewise constant per
// texel, so sample() and pdf() are exact: texels are picked proportionally to
// luminance x solid angle, then a direction uniformly inside the texel's solid angle.
#include <glm/glm.hpp>

#include <vector>

#include "phyir/core/image.h"
#include "phyir/render/sampling.h"

namespace phyir::render {

class EnvironmentLight {
 public:
  // `image`: linear RGB(A), any size >= 1x1. `scale` multiplies the radiance.
  EnvironmentLight(const Image& image, float scale = 1.0f);

  glm::vec3 radiance(const glm::vec3& direction) const;
  // Returns false if the environment is black everywhere.
  bool sample(const glm::vec2& u, glm::vec3* direction, glm::vec3* radiance, float* pdf) const;
  float pdf(const glm::vec3& direction) const;
  int width() const { return width_; }
  int height() const { return height_; }

 private:
  int width_ = 0, height_ = 0;
  std::vector<glm::vec3> texels_;
  Distribution1D rows_;                 // marginal over rows
  std::vector<Distribution1D> columns_; // conditional per row
};

}  // namespace phyir::render
