// The pixel sampler: uniform, stratified for every power-of-two count (one point in each
// elementary rectangle), different per pixel, and better than independent jitter at the
// task it exists for: the coverage of a pixel by a light's edge.
#include "phyir/render/pixel_sampler.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <set>
#include <vector>

#include "phyir/render/rng.h"

namespace phyir::render {
namespace {

TEST(PixelSampler, SobolDimension1ByteTablesEqualTheBitwiseMatrix) {
  Rng rng(7, 3);
  for (uint32_t i : {0u, 1u, 2u, 3u, 255u, 256u, 0x80000000u, 0xffffffffu})
    EXPECT_EQ(sobol_dimension1(i), sobol_dimension1_bitwise(i)) << i;
  for (int k = 0; k < 100000; ++k) {
    const uint32_t i = rng.next_u32();
    ASSERT_EQ(sobol_dimension1(i), sobol_dimension1_bitwise(i)) << i;
  }
}

TEST(PixelSampler, EveryPowerOfTwoPrefixHasOnePointInEachElementaryRectangle) {
  for (uint64_t key : {0ull, 1ull, 0x123456789abcdefull, ~0ull}) {
    for (int log2n = 0; log2n <= 8; ++log2n) {
      const int n = 1 << log2n;
      std::vector<glm::vec2> points;
      for (int i = 0; i < n; ++i) {
        const glm::vec2 p = pixel_sample(uint32_t(i), key);
        ASSERT_GE(p.x, 0.0f);
        ASSERT_LT(p.x, 1.0f);
        ASSERT_GE(p.y, 0.0f);
        ASSERT_LT(p.y, 1.0f);
        points.push_back(p);
      }
      // Rectangles of 2^a x 2^(log2n - a) cells, for every split a.
      for (int a = 0; a <= log2n; ++a) {
        const int nx = 1 << a, ny = n >> a;
        std::set<int> cells;
        for (const glm::vec2& p : points) cells.insert(int(p.y * ny) * nx + int(p.x * nx));
        EXPECT_EQ(cells.size(), size_t(n)) << "key " << key << ", n " << n << ", " << nx << "x" << ny;
      }
    }
  }
}

TEST(PixelSampler, PointsAreUniformOverPixelsAndDifferBetweenPixels) {
  // Sample 3 of many pixels: the mean of x, y and x*y of a uniform point is 1/2, 1/2, 1/4.
  constexpr int kPixels = 20000;
  double sx = 0, sy = 0, sxy = 0;
  std::set<std::pair<float, float>> distinct;
  for (int k = 0; k < kPixels; ++k) {
    const glm::vec2 p = pixel_sample(3, mix64(uint64_t(k)));
    sx += p.x;
    sy += p.y;
    sxy += double(p.x) * p.y;
    distinct.insert({p.x, p.y});
  }
  const double tolerance = 4.0 * std::sqrt(1.0 / 12.0 / kPixels);
  EXPECT_NEAR(sx / kPixels, 0.5, tolerance);
  EXPECT_NEAR(sy / kPixels, 0.5, tolerance);
  EXPECT_NEAR(sxy / kPixels, 0.25, tolerance);
  EXPECT_GT(distinct.size(), size_t(kPixels * 0.99));
}

// A light's straight edge across a pixel: the estimated covered fraction must be unbiased
// and have far less error than with independent jitter (16 samples).
TEST(PixelSampler, EstimatesTheCoverageOfAnEdgeFarBetterThanIndependentJitter) {
  constexpr int kPixels = 4000, kSpp = 16;
  double bias = 0, error2 = 0, jitter_error2 = 0;
  Rng edges(7, 1);
  for (int k = 0; k < kPixels; ++k) {
    // The half-plane below the line through (0.5, c) at angle t.
    const float c = edges.next_float(), t = (edges.next_float() - 0.5f) * 3.0f;
    const float slope = std::tan(t);
    auto covered = [&](const glm::vec2& p) { return p.y < c + slope * (p.x - 0.5f) ? 1.0 : 0.0; };
    // The exact fraction by fine quadrature.
    double truth = 0;
    for (int a = 0; a < 256; ++a) {
      const float x = (a + 0.5f) / 256.0f;
      truth += std::clamp(double(c + slope * (x - 0.5f)), 0.0, 1.0);
    }
    truth /= 256.0;
    double stratified = 0, jittered = 0;
    Rng jitter(mix64(uint64_t(k) + 99), 0);
    for (int s = 0; s < kSpp; ++s) {
      stratified += covered(pixel_sample(uint32_t(s), mix64(uint64_t(k))));
      jittered += covered(jitter.next_2d());
    }
    stratified /= kSpp;
    jittered /= kSpp;
    bias += stratified - truth;
    error2 += (stratified - truth) * (stratified - truth);
    jitter_error2 += (jittered - truth) * (jittered - truth);
  }
  const double rms = std::sqrt(error2 / kPixels), jitter_rms = std::sqrt(jitter_error2 / kPixels);
  std::cout << "edge coverage RMS error, 16 spp: stratified " << rms << ", independent jitter " << jitter_rms << "\n";
  EXPECT_NEAR(bias / kPixels, 0.0, 4.0 * rms / std::sqrt(double(kPixels)) + 1e-3);
  EXPECT_LT(rms, 0.6 * jitter_rms);
}

}  // namespace
}  // namespace phyir::render
