#pragma once
// Warps from [0,1)^2 to directions, each with its density. Tested by integrating the
// pdfs and by chi-square tests against sample histograms (tests/render/sampling_test.cpp).
#include <glm/glm.hpp>

#include <vector>

namespace phyir::render {

glm::vec2 sample_concentric_disk(const glm::vec2& u);

// Cosine-weighted hemisphere about +z; pdf = cos(theta) / pi.
glm::vec3 sample_cosine_hemisphere(const glm::vec2& u);
float cosine_hemisphere_pdf(float cos_theta);

// Uniform sphere; pdf = 1 / (4 pi).
glm::vec3 sample_uniform_sphere(const glm::vec2& u);
float uniform_sphere_pdf();

// Uniform over the cone of directions within angle acos(cos_max) of +z (cos_max = -1: the
// sphere); pdf = 1 / (2 pi (1 - cos_max)) inside it. Equal-area: a stratified u stays
// stratified in solid angle.
glm::vec3 sample_uniform_cone(const glm::vec2& u, float cos_max);
float uniform_cone_pdf(float cos_theta, float cos_max);

// GGX half-vector sampling about +z (eq. 18): pdf_h = D(n.h) (n.h).
glm::vec3 sample_ggx_half_vector(const glm::vec2& u, float alpha);

// Uniform point on a triangle: barycentrics (b1, b2) with b0 = 1 - b1 - b2.
glm::vec2 sample_uniform_triangle(const glm::vec2& u);

// Balance-free power heuristic (beta = 2) for multiple importance sampling.
float power_heuristic(float pdf_a, float pdf_b);
// The same with three strategies, one sample each: pdf_a^2 / (pdf_a^2 + pdf_b^2 + pdf_c^2);
// exactly the two-strategy weight where pdf_c is 0.
float power_heuristic(float pdf_a, float pdf_b, float pdf_c);

// A piecewise-constant 1D distribution, for light and environment sampling.
class Distribution1D {
 public:
  Distribution1D() = default;
  explicit Distribution1D(std::vector<float> weights);
  // Returns an index with probability weight/sum; `remapped` (optional) gets u rescaled to
  // [0,1) inside the chosen bin, to reuse the random number.
  int sample(float u, float* pmf = nullptr, float* remapped = nullptr) const;
  float pmf(int index) const;
  float total() const { return total_; }
  int size() const { return static_cast<int>(weights_.size()); }
  bool empty() const { return total_ <= 0.0f; }

 private:
  const float* upper_edge(float u) const;  // the first cdf_[i > 0] above u, or the end
  std::vector<float> weights_;
  std::vector<float> cdf_;  // size() + 1 entries, cdf_[0] = 0, cdf_.back() = 1
  float total_ = 0.0f;
};

}  // namespace phyir::render
