// Warps of render/src/sampling.cpp: every pdf integrates to 1, every sampler matches its
// pdf under a chi-square test (p >= 1e-3, see chi_square.h), and the chi-square helper
// itself reproduces textbook p-values and rejects a wrong pdf.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "chi_square.h"
#include "phyir/core/safe_math.h"
#include "phyir/render/alias_table.h"
#include "phyir/render/brdf.h"
#include "phyir/render/rng.h"
#include "phyir/render/sampling.h"

namespace phyir::render {
namespace {

using test::chi_square_directions;
using test::chi_square_p_value;
using test::SphereGrid;

constexpr int kChiSamples = 1000000;
constexpr double kSignificance = 1e-3;

// pdf_h of GGX half-vector sampling, eq. 18: D(n.h) (n.h), with eq. 15 written out in
// double from h's components: D_GGX(NoH) cannot resolve alpha < ~3e-4 from a float NoH
// (one ulp below 1 is a 3.5e-4 rad step), and the sampler must be checked below that.
double ggx_half_pdf(const glm::vec3& h, float alpha) {
  if (h.z <= 0.0f) return 0.0;
  const double a2 = double(alpha) * alpha, cos2 = double(h.z) * h.z;
  const double sin2 = double(h.x) * h.x + double(h.y) * h.y, len2 = cos2 + sin2;
  const double d = (cos2 * a2 + sin2) / len2;
  return a2 / (3.14159265358979323846 * d * d) * (h.z / std::sqrt(len2));
}

// --- the chi-square helper ----------------------------------------------------------------

TEST(ChiSquareHelper, ReproducesTablePValues) {
  // Critical values of the chi-square distribution at 5% and 0.1% (any statistics table).
  EXPECT_NEAR(chi_square_p_value(3.841459, 1), 0.05, 1e-6);
  EXPECT_NEAR(chi_square_p_value(18.307038, 10), 0.05, 1e-6);
  EXPECT_NEAR(chi_square_p_value(124.342113, 100), 0.05, 1e-6);
  EXPECT_NEAR(chi_square_p_value(10.827566, 1), 1e-3, 1e-8);
  // dof = 2 is an exponential: p = exp(-x/2).
  for (double x : {0.1, 1.0, 5.0, 30.0}) {
    EXPECT_NEAR(chi_square_p_value(x, 2), std::exp(-0.5 * x), 1e-12) << x;
  }
  EXPECT_DOUBLE_EQ(chi_square_p_value(0.0, 5), 1.0);
}

TEST(ChiSquareHelper, PoolsSmallCellsAndFailsOnImpossibleSamples) {
  const auto ok = test::chi_square_test({100, 98, 3, 1, 2}, {100, 100, 2, 2, 2});
  EXPECT_EQ(ok.pooled_cells, 3);
  EXPECT_EQ(ok.dof, 2);  // two big cells + one pool of the three small ones, minus 1
  EXPECT_TRUE(ok.passed(kSignificance)) << ok.message;
  const auto bad = test::chi_square_test({100, 100, 1}, {100, 101, 0});
  EXPECT_EQ(bad.impossible_samples, 1);
  EXPECT_FALSE(bad.passed(kSignificance));
}

TEST(ChiSquareHelper, RejectsAWrongPdf) {
  // Cosine-distributed samples tested against the uniform hemisphere pdf must fail, or the
  // chi-square tests below prove nothing.
  Rng rng(7, 1);
  const SphereGrid grid(glm::vec3(0, 0, 1), 1.0f, 16, 32);
  const auto r = chi_square_directions(
      grid, 100000,
      [&](int, glm::vec3* w, bool*) {
        *w = sample_cosine_hemisphere(rng.next_2d());
        return true;
      },
      [](const glm::vec3& w) { return w.z > 0.0f ? 1.0 / (2.0 * kPi) : 0.0; });
  EXPECT_FALSE(r.passed(kSignificance)) << r.message;
}

// --- pdfs integrate to 1 -------------------------------------------------------------------

TEST(SamplingPdf, CosineHemisphereIntegratesToOne) {
  const SphereGrid grid(glm::vec3(0, 0, 1), 1.0f, 200, 64);  // horizon on a cell edge
  const double integral =
      grid.integrate([](const glm::vec3& w) { return double(cosine_hemisphere_pdf(w.z)); }, 2);
  EXPECT_NEAR(integral, 1.0, 1e-4);
}

TEST(SamplingPdf, UniformSphereIntegratesToOne) {
  const SphereGrid grid(glm::vec3(0, 0, 1), 1.0f, 100, 64);
  const double integral = grid.integrate([](const glm::vec3&) { return double(uniform_sphere_pdf()); }, 2);
  EXPECT_NEAR(integral, 1.0, 1e-4);
}

TEST(SamplingPdf, UniformConeIntegratesToOne) {
  // Half-angles on the grid's rows (pi k / 100), so the cone's edge falls on a cell edge.
  for (int k : {10, 25, 50, 80, 100}) {
    const float cos_max = float(std::cos(3.14159265358979323846 * k / 100.0));
    const SphereGrid grid(glm::vec3(0, 0, 1), 1.0f, 100, 64);
    const double integral =
        grid.integrate([&](const glm::vec3& w) { return double(uniform_cone_pdf(w.z, cos_max)); }, 2);
    EXPECT_NEAR(integral, 1.0, 1e-3) << "half-angle pi " << k << " / 100";
  }
}

TEST(SamplingPdf, GgxHalfVectorIntegratesToOne) {
  // alpha = R^2 for R = 1, 0.5, 0.3, 0.05, 0.01. A grid packed towards +z (theta ~ x^4)
  // resolves even the alpha = 1e-4 lobe.
  for (float alpha : {1.0f, 0.25f, 0.09f, 0.0025f, 1e-4f}) {
    const SphereGrid grid(glm::vec3(0, 0, 1), 4.0f, 400, 8);
    const double integral = grid.integrate([&](const glm::vec3& h) { return ggx_half_pdf(h, alpha); }, 2);
    // The float D_GGX agrees wherever its NoH can resolve the lobe.
    if (alpha >= 0.0025f) {
      EXPECT_NEAR(grid.integrate([&](const glm::vec3& h) { return h.z > 0 ? double(D_GGX(h.z, alpha)) * h.z : 0.0; }, 2),
                  1.0, 1e-3)
          << "alpha = " << alpha;
    }
    EXPECT_NEAR(integral, 1.0, 1e-3) << "alpha = " << alpha;
  }
}

// --- chi-square tests of the samplers ------------------------------------------------------

TEST(SamplingChiSquare, CosineHemisphere) {
  Rng rng(11, 2);
  const SphereGrid grid(glm::vec3(0, 0, 1), 1.0f, 32, 64);
  const auto r = chi_square_directions(
      grid, kChiSamples,
      [&](int, glm::vec3* w, bool*) {
        *w = sample_cosine_hemisphere(rng.next_2d());
        return true;
      },
      [](const glm::vec3& w) { return double(cosine_hemisphere_pdf(w.z)); });
  std::printf("[chi2] cosine hemisphere: %s\n", r.message.c_str());
  EXPECT_TRUE(r.passed(kSignificance)) << r.message;
}

TEST(SamplingChiSquare, UniformSphere) {
  Rng rng(12, 3);
  const SphereGrid grid(glm::vec3(0, 0, 1), 1.0f, 32, 64);
  const auto r = chi_square_directions(
      grid, kChiSamples,
      [&](int, glm::vec3* w, bool*) {
        *w = sample_uniform_sphere(rng.next_2d());
        return true;
      },
      [](const glm::vec3&) { return double(uniform_sphere_pdf()); });
  std::printf("[chi2] uniform sphere: %s\n", r.message.c_str());
  EXPECT_TRUE(r.passed(kSignificance)) << r.message;
}

TEST(SamplingChiSquare, UniformCone) {
  // Half-angles on the grid's rows (pi k / 32): a cell the cone's edge cut would hold a
  // discontinuity the helper's integration of the pdf over the cell cannot resolve.
  for (const int k : {4, 12, 22}) {
    // Rounded up, so no sample on the edge falls in the row beyond it.
    const float cos_max = std::nextafter(float(std::cos(3.14159265358979323846 * k / 32.0)), 1.0f);
    Rng rng(13, 4);
    const SphereGrid grid(glm::vec3(0, 0, 1), 1.0f, 32, 64);
    const auto r = chi_square_directions(
        grid, kChiSamples,
        [&](int, glm::vec3* w, bool*) {
          *w = sample_uniform_cone(rng.next_2d(), cos_max);
          return true;
        },
        [&](const glm::vec3& w) { return double(uniform_cone_pdf(w.z, cos_max)); });
    std::printf("[chi2] uniform cone, cos_max %.1f: %s\n", cos_max, r.message.c_str());
    EXPECT_TRUE(r.passed(kSignificance)) << r.message;
  }
}

TEST(SamplingChiSquare, GgxHalfVector) {
  // Rough lobes on the plain (theta, phi) grid; narrow ones on a grid packed towards +z.
  // alpha = 1e-4 (R = 0.01) failed before the sampler's small-alpha fix: the old
  // cos^2 = (1 - u) / (1 + (alpha^2 - 1) u) rounded every sample to the normal.
  struct Case {
    float alpha, power;
  };
  int seed = 100;
  for (const Case c : {Case{1.0f, 1.0f}, Case{0.25f, 1.0f}, Case{0.09f, 2.0f},
                       Case{0.0025f, 4.0f}, Case{1e-4f, 4.0f}}) {
    Rng rng(seed++, 4);
    const SphereGrid grid(glm::vec3(0, 0, 1), c.power, 32, 32);
    const auto r = chi_square_directions(
        grid, kChiSamples,
        [&](int, glm::vec3* h, bool*) {
          *h = sample_ggx_half_vector(rng.next_2d(), c.alpha);
          return true;
        },
        [&](const glm::vec3& h) { return ggx_half_pdf(h, c.alpha); });
    std::printf("[chi2] ggx half vector alpha=%g: %s\n", c.alpha, r.message.c_str());
    EXPECT_TRUE(r.passed(kSignificance)) << "alpha = " << c.alpha << ": " << r.message;
  }
}

TEST(SamplingGgx, FiniteAndUnitForEveryAlphaAndU) {
  for (float alpha : {0.0f, 1e-6f, 1e-4f, 0.5f, 1.0f}) {
    for (float ux : {0.0f, 0.5f, 0x1.fffffep-1f, 1.0f}) {
      const glm::vec3 h = sample_ggx_half_vector(glm::vec2(ux, 0.3f), alpha);
      ASSERT_TRUE(is_finite(h)) << alpha << " " << ux;
      EXPECT_NEAR(glm::length(h), 1.0f, 1e-5f) << alpha << " " << ux;
      EXPECT_GE(h.z, 0.0f);
    }
  }
}

// --- triangle, 1D distribution, MIS --------------------------------------------------------

TEST(SamplingTriangle, UniformOverSubTriangles) {
  // Cut [0,1]^2 into n x n squares and each square into a lower and an upper triangle by
  // its anti-diagonal: the n^2 sub-triangles inside b1 + b2 <= 1 have equal area and
  // must fill equally; the others must stay empty.
  constexpr int n = 16;
  constexpr int samples = 512000;
  std::vector<double> observed(2 * n * n, 0.0), expected(2 * n * n, 0.0);
  for (int ix = 0; ix < n; ++ix) {
    for (int iy = 0; ix + iy < n; ++iy) {
      expected[(ix * n + iy) * 2] = double(samples) / (n * n);
      if (ix + iy < n - 1) expected[(ix * n + iy) * 2 + 1] = double(samples) / (n * n);
    }
  }
  Rng rng(21, 5);
  for (int i = 0; i < samples; ++i) {
    const glm::vec2 b = sample_uniform_triangle(rng.next_2d());
    ASSERT_GE(b.x, 0.0f);
    ASSERT_GE(b.y, 0.0f);
    ASSERT_LE(b.x + b.y, 1.0f + 1e-6f);
    const double sx = double(b.x) * n, sy = double(b.y) * n;
    const int ix = std::min(int(sx), n - 1), iy = std::min(int(sy), n - 1);
    const bool upper = (sx - ix) + (sy - iy) > 1.0;
    observed[(ix * n + iy) * 2 + (upper ? 1 : 0)] += 1.0;
  }
  const auto r = test::chi_square_test(observed, expected);
  EXPECT_TRUE(r.passed(kSignificance)) << r.message;
}

// One draw: Distribution1D takes one uniform (`first`, else from rng), AliasTable two.
int draw(const Distribution1D& d, Rng& rng, float* pmf, float* remapped, float first = -1.0f) {
  return d.sample(first >= 0.0f ? first : rng.next_float(), pmf, remapped);
}
int draw(const AliasTable& d, Rng& rng, float* pmf, float* remapped, float first = -1.0f) {
  const float u_bin = first >= 0.0f ? first : rng.next_float();
  return d.sample(u_bin, rng.next_float(), pmf, remapped);
}

// Distribution1D (cdf inversion) and AliasTable (Walker) promise the same: indices with
// probability weight / sum, zero bins never, a remapped variate uniform given the index.
template <typename Distribution>
void expect_draws_match_weights() {
  const std::vector<float> w = {0.0f, 1.0f, 3.0f, 0.0f, 0.5f, 2.5f, 0.0f};
  const Distribution d(w);
  EXPECT_FLOAT_EQ(float(d.total()), 7.0f);
  EXPECT_FLOAT_EQ(d.pmf(2), 3.0f / 7.0f);
  EXPECT_EQ(d.pmf(-1), 0.0f);
  EXPECT_EQ(d.pmf(7), 0.0f);
  constexpr int samples = 700000;
  std::vector<double> observed(w.size(), 0.0), expected(w.size());
  for (size_t i = 0; i < w.size(); ++i) expected[i] = samples * w[i] / 7.0;
  Rng rng(31, 6);
  double remapped_sum = 0.0;
  std::vector<double> remapped_by_index(w.size(), 0.0);
  for (int i = 0; i < samples; ++i) {
    float pmf = 0.0f, remapped = -1.0f;
    const int k = draw(d, rng, &pmf, &remapped);
    ASSERT_GE(k, 0);
    ASSERT_GT(w[k], 0.0f);
    ASSERT_FLOAT_EQ(pmf, w[k] / 7.0f);
    ASSERT_GE(remapped, 0.0f);
    ASSERT_LT(remapped, 1.0f);
    remapped_sum += remapped;
    remapped_by_index[k] += remapped;
    observed[k] += 1.0;
  }
  const auto r = test::chi_square_test(observed, expected);
  EXPECT_TRUE(r.passed(kSignificance)) << r.message;
  // The remapped variate is uniform: mean 1/2 within 5 sigma (sigma = 1/sqrt(12 n)).
  EXPECT_NEAR(remapped_sum / samples, 0.5, 5.0 / std::sqrt(12.0 * samples));
  for (size_t k = 0; k < w.size(); ++k) {  // and uniform given each index
    if (observed[k] > 0) {
      EXPECT_NEAR(remapped_by_index[k] / observed[k], 0.5, 5.0 / std::sqrt(12.0 * observed[k])) << k;
    }
  }
  // The ends of [0, 1) land in non-empty bins.
  for (float u : {0.0f, 0x1.fffffep-1f}) {
    Rng ends(u > 0.5f ? 1 : 2, 3);
    EXPECT_GT(w[size_t(draw(d, ends, nullptr, nullptr, u))], 0.0f) << u;
  }
  EXPECT_EQ(draw(Distribution(std::vector<float>{0.0f, 0.0f}), rng, nullptr, nullptr), -1);
}

TEST(SamplingDistribution1D, MatchesWeightsAndSkipsZeroBins) { expect_draws_match_weights<Distribution1D>(); }
TEST(SamplingAliasTable, MatchesWeightsAndSkipsZeroBins) { expect_draws_match_weights<AliasTable>(); }

// The branch-free search finds the bin std::upper_bound finds over the same cdf (built here
// as the constructor builds it), at random u, at the cdf's own edges and at the ends, for
// sizes around powers of two and with runs of zero weights.
TEST(SamplingDistribution1D, SearchFindsUpperBoundsBin) {
  Rng rng(41, 2);
  for (int n : {1, 2, 3, 4, 5, 7, 8, 9, 16, 17, 31, 100, 1000, 1023, 1025}) {
    std::vector<float> w(static_cast<size_t>(n));
    for (float& x : w) x = rng.next_float() < 0.3f ? 0.0f : rng.next_float();
    w[size_t(rng.below(uint32_t(n)))] = 1.0f;
    std::vector<float> cdf(w.size() + 1, 0.0f);
    double sum = 0.0;
    for (size_t i = 0; i < w.size(); ++i) cdf[i + 1] = float(sum += w[i]);
    for (float& c : cdf) c = float(c / sum);
    cdf.back() = 1.0f;
    const Distribution1D d(w);
    std::vector<float> us = {0.0f, 0x1.fffffep-1f};
    for (float c : cdf) us.push_back(c);
    for (int k = 0; k < 2000; ++k) us.push_back(rng.next_float());
    for (float u : us) {
      if (!(u < 1.0f)) continue;
      int expected = int(std::upper_bound(cdf.begin() + 1, cdf.end(), u) - cdf.begin()) - 1;
      expected = std::clamp(expected, 0, n - 1);
      while (expected > 0 && w[size_t(expected)] == 0.0f) --expected;
      ASSERT_EQ(d.sample(u), expected) << "n " << n << ", u " << u;
    }
  }
}

// A large table of very unequal weights (an HDR sky with a sun): pmfs as given, and the
// draws' histogram matches them.
TEST(SamplingAliasTable, LargeSkewedTable) {
  std::vector<float> w(4096);
  Rng weights_rng(5, 1);
  for (float& x : w) x = weights_rng.next_float() < 0.3f ? 0.0f : std::pow(weights_rng.next_float(), 8.0f);
  w[1234] = 5000.0f;  // the sun
  const AliasTable table(w);
  const Distribution1D reference(w);
  std::vector<double> observed(w.size(), 0.0), expected(w.size());
  constexpr int samples = 2000000;
  for (size_t i = 0; i < w.size(); ++i) {
    EXPECT_NEAR(table.pmf(int(i)), reference.pmf(int(i)), 1e-6f * reference.pmf(int(i)) + 1e-12f) << i;
    expected[i] = samples * double(reference.pmf(int(i)));
  }
  Rng rng(7, 3);
  for (int i = 0; i < samples; ++i) {
    const int k = draw(table, rng, nullptr, nullptr);
    ASSERT_GT(w[size_t(k)], 0.0f) << k;
    observed[size_t(k)] += 1.0;
  }
  const auto r = test::chi_square_test(observed, expected);
  EXPECT_TRUE(r.passed(kSignificance)) << r.message;
}

TEST(SamplingMis, PowerHeuristic) {
  EXPECT_FLOAT_EQ(power_heuristic(1.0f, 1.0f), 0.5f);
  EXPECT_FLOAT_EQ(power_heuristic(3.0f, 1.0f), 0.9f);
  EXPECT_FLOAT_EQ(power_heuristic(0.0f, 0.0f), 0.0f);
  EXPECT_FLOAT_EQ(power_heuristic(INFINITY, 1.0f), 1.0f);
  EXPECT_FLOAT_EQ(power_heuristic(1e30f, 1.0f), 1.0f);  // a^2 overflows
}

}  // namespace
}  // namespace phyir::render
