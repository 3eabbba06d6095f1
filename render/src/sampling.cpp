#include "phyir/render/sampling.h"

#include <algorithm>
#include <cmath>

#include "phyir/core/safe_math.h"

namespace phyir::render {

glm::vec2 sample_concentric_disk(const glm::vec2& u) {
  // Shirley & Chiu 1997: maps squares to rings, keeping strata compact.
  const glm::vec2 o = 2.0f * u - glm::vec2(1.0f);
  if (o.x == 0.0f && o.y == 0.0f) return glm::vec2(0.0f);
  float r, theta;
  if (std::abs(o.x) > std::abs(o.y)) {
    r = o.x;
    theta = 0.25f * kPi * (o.y / o.x);
  } else {
    r = o.y;
    theta = 0.5f * kPi - 0.25f * kPi * (o.x / o.y);
  }
  return r * glm::vec2(std::cos(theta), std::sin(theta));
}

glm::vec3 sample_cosine_hemisphere(const glm::vec2& u) {
  // Malley's method: project the uniform disk up onto the hemisphere.
  const glm::vec2 d = sample_concentric_disk(u);
  return glm::vec3(d.x, d.y, safe_sqrt(1.0f - d.x * d.x - d.y * d.y));
}

float cosine_hemisphere_pdf(float cos_theta) { return cos_theta > 0.0f ? cos_theta * kInvPi : 0.0f; }

glm::vec3 sample_uniform_sphere(const glm::vec2& u) { return sample_uniform_cone(u, -1.0f); }

float uniform_sphere_pdf() { return 1.0f / (4.0f * kPi); }

glm::vec3 sample_uniform_cone(const glm::vec2& u, float cos_max) {
  const float z = std::max(cos_max, 1.0f - u.x * (1.0f - cos_max));  // rounding never leaves the cone
  const float r = safe_sqrt(1.0f - z * z);
  const float phi = kTwoPi * u.y;
  return glm::vec3(r * std::cos(phi), r * std::sin(phi), z);
}

float uniform_cone_pdf(float cos_theta, float cos_max) {
  return cos_theta >= cos_max && cos_max < 1.0f ? 1.0f / (kTwoPi * (1.0f - cos_max)) : 0.0f;
}

glm::vec3 sample_ggx_half_vector(const glm::vec2& u, float alpha) {
  // Invert the GGX cdf in theta_h: tan^2 = alpha^2 u / (1 - u) (Walter et al. 2007),
  // written as cos^2 = (1 - u) / d and sin^2 = alpha^2 u / d with d = (1 - u) + alpha^2 u,
  // so it stays finite at u -> 1 and keeps full precision for small alpha. (The form
  // (1 - u) / (1 + (alpha^2 - 1) u) rounds alpha^2 - 1 to -1 for alpha < 2.4e-4, i.e.
  // roughness < 0.0155, collapsing the lobe to a mirror; and sqrt(1 - cos^2) quantises
  // sin(theta), its smallest non-zero value being 2.4e-4: both fail the chi-square tests
  // in tests/render/sampling_test.cpp at alpha = 0.0025 and 1e-4.)
  const float a2 = alpha * alpha;
  const float one_minus_u = 1.0f - u.x;
  const float d = one_minus_u + a2 * u.x;
  if (!(d > 0.0f)) return glm::vec3(0.0f, 0.0f, 1.0f);  // alpha = 0: the mirror normal
  const float cos_theta = safe_sqrt(one_minus_u / d);
  const float sin_theta = safe_sqrt(a2 * u.x / d);
  const float phi = kTwoPi * u.y;
  return glm::vec3(sin_theta * std::cos(phi), sin_theta * std::sin(phi), cos_theta);
}

glm::vec2 sample_uniform_triangle(const glm::vec2& u) {
  // Heitz 2019's low-distortion square-to-triangle map.
  float b0, b1;
  if (u.x < u.y) {
    b0 = u.x / 2.0f;
    b1 = u.y - b0;
  } else {
    b1 = u.y / 2.0f;
    b0 = u.x - b1;
  }
  return glm::vec2(b1, 1.0f - b0 - b1);
}

float power_heuristic(float pdf_a, float pdf_b, float pdf_c) {
  if (pdf_c == 0.0f) return power_heuristic(pdf_a, pdf_b);
  const float a2 = pdf_a * pdf_a;
  if (std::isinf(a2)) return 1.0f;
  return safe_div(a2, a2 + pdf_b * pdf_b + pdf_c * pdf_c);
}

float power_heuristic(float pdf_a, float pdf_b) {
  const float a2 = pdf_a * pdf_a;
  const float b2 = pdf_b * pdf_b;
  if (std::isinf(a2)) return 1.0f;
  return safe_div(a2, a2 + b2);
}

Distribution1D::Distribution1D(std::vector<float> weights) : weights_(std::move(weights)) {
  cdf_.assign(weights_.size() + 1, 0.0f);
  double sum = 0.0;
  for (size_t i = 0; i < weights_.size(); ++i) {
    const float w = std::isfinite(weights_[i]) ? std::max(weights_[i], 0.0f) : 0.0f;
    weights_[i] = w;
    sum += w;
    cdf_[i + 1] = static_cast<float>(sum);
  }
  total_ = static_cast<float>(sum);
  if (sum > 0.0) {
    for (float& c : cdf_) c = static_cast<float>(c / sum);
  }
  cdf_.back() = 1.0f;
}

// std::upper_bound over cdf_[1..] without branches: the loop runs log2(size) times whatever
// u is and each step is a conditional move, where a search over an emitter cluster's
// hundreds of triangles otherwise mispredicts about every other step. Same answer.
const float* Distribution1D::upper_edge(float u) const {
  const float* first = cdf_.data() + 1;
  size_t n = cdf_.size() - 1;  // >= 1: not empty
  // The answer stays in [first, first + n].
  while (n > 1) {
    const size_t half = n / 2;
    first = !(u < first[half]) ? first + half : first;  // upper_bound's own test
    n -= half;
  }
  return first + (!(u < *first) ? 1 : 0);
}

int Distribution1D::sample(float u, float* pmf, float* remapped) const {
  if (empty()) {
    if (pmf) *pmf = 0.0f;
    return -1;
  }
  // First bin whose upper cdf edge exceeds u; zero-weight bins can never be chosen.
  int index = static_cast<int>(upper_edge(u) - cdf_.data()) - 1;
  index = std::clamp(index, 0, size() - 1);
  while (index > 0 && weights_[index] == 0.0f) index -= 1;  // guards u == 1 - epsilon rounding
  if (pmf) *pmf = weights_[index] / total_;
  if (remapped) {
    const float width = cdf_[index + 1] - cdf_[index];
    *remapped = width > 0.0f ? std::min((u - cdf_[index]) / width, kOneMinusEpsilon) : 0.0f;
  }
  return index;
}

float Distribution1D::pmf(int index) const {
  if (empty() || index < 0 || index >= size()) return 0.0f;
  return weights_[index] / total_;
}

}  // namespace phyir::render
