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

  // Texel weight = luminance x texel solid angle; the marginal over rows sums each row.
  std::vector<float> row_weights(height_);
  columns_.reserve(height_);
  for (int y = 0; y < height_; ++y) {
    const float solid_angle = equirect_texel_solid_angle(y, width_, height_);
    std::vector<float> w(width_);
    double sum = 0.0;
    for (int x = 0; x < width_; ++x) {
      w[x] = luminance(texels_[static_cast<size_t>(y) * width_ + x]) * solid_angle;
      sum += w[x];
    }
    row_weights[y] = static_cast<float>(sum);
    columns_.emplace_back(std::move(w));
  }
  rows_ = Distribution1D(std::move(row_weights));
}

glm::vec3 EnvironmentLight::radiance(const glm::vec3& direction) const {
  const glm::ivec2 t = texel_of(direction, width_, height_);
  return texels_[static_cast<size_t>(t.y) * width_ + t.x];
}

bool EnvironmentLight::sample(const glm::vec2& u, glm::vec3* direction, glm::vec3* radiance, float* pdf) const {
  if (rows_.empty()) return false;
  float pmf_row = 0.0f, pmf_col = 0.0f, u_row = 0.0f, u_col = 0.0f;
  const int row = rows_.sample(u.y, &pmf_row, &u_row);
  const int col = columns_[row].sample(u.x, &pmf_col, &u_col);
  if (row < 0 || col < 0) return false;

  // Uniform inside the texel's solid angle: phi uniform across the column, cos(theta)
  // uniform across the row's band (Archimedes: equal cos bands have equal area).
  const double cos_top = std::cos(kPi * double(row) / height_);
  const double cos_bottom = std::cos(kPi * double(row + 1) / height_);
  const float cos_theta = static_cast<float>(cos_top + (cos_bottom - cos_top) * double(u_row));
  const float sin_theta = safe_sqrt(1.0f - cos_theta * cos_theta);
  const float uu = (static_cast<float>(col) + u_col) / static_cast<float>(width_);
  const float phi = (uu - 0.5f) * kTwoPi;  // equirect.h: 0 along -Z, growing towards +X
  *direction = glm::vec3(sin_theta * std::sin(phi), cos_theta, -sin_theta * std::cos(phi));

  const float solid_angle = equirect_texel_solid_angle(row, width_, height_);
  *pdf = safe_div(pmf_row * pmf_col, solid_angle);
  *radiance = texels_[static_cast<size_t>(row) * width_ + col];
  return *pdf > 0.0f;
}

float EnvironmentLight::pdf(const glm::vec3& direction) const {
  if (rows_.empty()) return 0.0f;
  const glm::ivec2 t = texel_of(direction, width_, height_);
  return safe_div(rows_.pmf(t.y) * columns_[t.y].pmf(t.x), equirect_texel_solid_angle(t.y, width_, height_));
}

}  // namespace phyir::render
