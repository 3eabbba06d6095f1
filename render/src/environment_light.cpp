#include "phyir/render/environment_light.h"

#include <algorithm>
#include <cmath>

#include "phyir/core/error.h"
#include "phyir/core/safe_math.h"
#include "phyir/render/equirect.h"

namespace phyir::render {

namespace {

// The texel (column, row) a direction falls in; the same rounding for radiance() and pdf().
glm::ivec2 texel_of(const glm::vec3& direction, int width, int height) {
  const glm::vec2 uv = equirect_uv(direction);
  const int col = std::clamp(static_cast<int>(uv.x * static_cast<float>(width)), 0, width - 1);
  const int row = std::clamp(static_cast<int>(uv.y * static_cast<float>(height)), 0, height - 1);
  return glm::ivec2(col, row);
}

}  // namespace

EnvironmentLight::EnvironmentLight(const Image& image, float scale) {
  if (image.width < 1 || image.height < 1 || image.channels < 1 ||
      image.pixels.size() < static_cast<size_t>(image.width) * image.height * image.channels)
    fail("environment: image of {}x{}x{} with {} values is not a usable equirect map", image.width,
         image.height, image.channels, image.pixels.size());
  width_ = image.width;
  height_ = image.height;
  texels_.resize(static_cast<size_t>(width_) * height_);
  for (int y = 0; y < height_; ++y) {
    for (int x = 0; x < width_; ++x) {
      glm::vec3 c;
      if (image.channels >= 3) {
        c = glm::vec3(image.at(x, y, 0), image.at(x, y, 1), image.at(x, y, 2));
      } else {
        c = glm::vec3(image.at(x, y, 0));  // grey (and grey + alpha)
      }
      c *= scale;
      // Negative or non-finite radiance is not light: it would break the sampling pdf.
      for (int k = 0; k < 3; ++k)
        if (!std::isfinite(c[k]) || c[k] < 0.0f) c[k] = 0.0f;
      texels_[static_cast<size_t>(y) * width_ + x] = c;
    }
  }

  // Texel weight = luminance x texel solid angle.
  std::vector<float> weights(texels_.size());
  for (int y = 0; y < height_; ++y) {
    solid_angles_.push_back(equirect_texel_solid_angle(y, width_, height_));
    cos_edges_.push_back(std::cos(kPi * double(y) / height_));
    for (int x = 0; x < width_; ++x) {
      const size_t i = static_cast<size_t>(y) * width_ + x;
      weights[i] = luminance(texels_[i]) * solid_angles_.back();
    }
  }
  cos_edges_.push_back(-1.0);
  choice_ = AliasTable(weights);
}

glm::vec3 EnvironmentLight::radiance(const glm::vec3& direction) const {
  const glm::ivec2 t = texel_of(direction, width_, height_);
  return texels_[static_cast<size_t>(t.y) * width_ + t.x];
}

bool EnvironmentLight::sample(const glm::vec3& u, glm::vec3* direction, glm::vec3* radiance, float* pdf) const {
  float pmf = 0.0f, u_theta = 0.0f;
  const int texel = choice_.sample(u.x, u.y, &pmf, &u_theta);
  if (texel < 0) return false;
  const int row = texel / width_, col = texel % width_;
  // Uniform inside the texel's solid angle: cos(theta) uniform across the row's band
  // (Archimedes: equal cos bands have equal area; the draw's remapped number), phi uniform
  // across the column (u.z).
  const double cos_top = cos_edges_[size_t(row)], cos_bottom = cos_edges_[size_t(row) + 1];
  const float cos_theta = static_cast<float>(cos_top + (cos_bottom - cos_top) * double(u_theta));
  const float sin_theta = safe_sqrt(1.0f - cos_theta * cos_theta);
  const float uu = (static_cast<float>(col) + u.z) / static_cast<float>(width_);
  const float phi = (uu - 0.5f) * kTwoPi;  // equirect.h: 0 along -Z, growing towards +X
  *direction = glm::vec3(sin_theta * std::sin(phi), cos_theta, -sin_theta * std::cos(phi));
  *pdf = safe_div(pmf, solid_angles_[size_t(row)]);
  *radiance = texels_[size_t(texel)];
  return *pdf > 0.0f;
}

void EnvironmentLight::prefetch(const glm::vec3& u) const {
  const int texel = choice_.prefetch(u.x);
  if (texel >= 0) __builtin_prefetch(&texels_[size_t(texel)]);
}

float EnvironmentLight::pdf(const glm::vec3& direction) const {
  if (choice_.empty()) return 0.0f;
  const glm::ivec2 t = texel_of(direction, width_, height_);
  return safe_div(choice_.pmf(t.y * width_ + t.x), solid_angles_[size_t(t.y)]);
}

}  // namespace phyir::render
