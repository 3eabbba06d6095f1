// The UE4 metalness BRDF (render/src/brdf.cpp, paper appendix A.3, eq. 13-18):
//   terms     each named term against values computed by hand from the equations;
//   eval      assembly of eq. 14 at a hand-computed point, reciprocity, zero below;
//   pdf       brdf_pdf integrates to 1 minus the specular lobe's below-horizon leak,
//             which is computed independently in half-vector space;
//   sampling  chi-square of brdf_sample against brdf_pdf (p >= 1e-3, chi_square.h);
//   weights   sample weight == eval cos / pdf; E[weight] == directional albedo by
//             quadrature (white furnace of the BRDF alone) within 4.5 standard errors;
//   energy    metals reflect <= 1; dielectrics = Lambert B + specular (may exceed 1);
//   mirror    the roughness < kMirrorRoughness branch is the limit of the rough lobe;
//   sweep     every output finite and non-negative at the parameter and angle extremes;
//   specular  the specular lobe alone (specular_eval/pdf/sample, specular_albedo): f_s =
//             f_r - f_d without cancellation, its pdf integrates to the samples' acceptance
//             rate, the albedo table against quadrature.
// Quadrature and chi-square cells use LobeGrid (chi_square.h): (theta, phi) cells packed
// around the mirror direction at the lobe's scale, with the horizon on the grid's edge, so
// narrow lobes and the pdf's jump at the horizon cost no more than a smooth integrand.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "chi_square.h"
#include "phyir/core/safe_math.h"
#include "phyir/render/brdf.h"
#include "phyir/render/rng.h"
#include "phyir/render/sampling.h"

namespace phyir::render {
namespace {

using test::LobeGrid;

constexpr double kPiD = 3.14159265358979323846;
constexpr double kSignificance = 1e-3;

glm::vec3 view_dir(float NoV, float phi = 0.3f) {
  const float s = safe_sqrt(1.0f - NoV * NoV);
  return glm::vec3(s * std::cos(phi), s * std::sin(phi), NoV);
}

glm::vec3 mirror_of(const glm::vec3& wo) { return glm::vec3(-wo.x, -wo.y, wo.z); }

BrdfParams params(float R, float M, glm::vec3 B = glm::vec3(1.0f)) {
  BrdfParams p;
  p.base_color = B;
  p.roughness = R;
  p.metalness = M;
  return p;
}

// k of eq. 17, written out independently of brdf.cpp.
double k_of(double R) { return (R + 1.0) * (R + 1.0) / 8.0; }

// A (theta, phi) grid over the hemisphere packed around the mirror direction of wo at the
// scale of the specular lobe, with BRDF's cut-off z = kMinCosine on its edge. Reflecting wo about h = n + e moves wi
// by 2|e| along theta but only by 2 NoV |e| across (wo.h is stationary for a sideways
// tilt), so the lobe is ~2 alpha by ~2 alpha NoV: 10x narrower across at NoV = 0.05.
LobeGrid lobe_grid(const BrdfParams& p, const glm::vec3& wo, int n = 64) {
  const double alpha = is_mirror(p.roughness) ? 0.5 : double(p.roughness) * p.roughness;
  const double w = std::clamp(2.0 * alpha, 1e-5, 1.0);
  return LobeGrid(mirror_of(wo), w, w * std::max(double(wo.z), 1e-3), n, n, kMinCosine);
}

// Directional albedo: integral of f_r cos over the hemisphere (quadrature) plus, for the
// mirror branch, the delta lobe's F(NoV) G1(NoV)^2.
glm::dvec3 albedo_quadrature(const BrdfParams& p, const glm::vec3& wo, int n = 96, int sub = 4) {
  glm::dvec3 sum = test::integrate_grid<glm::dvec3>(
      lobe_grid(p, wo, n), [&](const glm::vec3& wi) { return glm::dvec3(brdf_eval(p, wo, wi)) * double(wi.z); },
      sub);
  if (is_mirror(p.roughness)) {
    const float G1 = G1_SmithSchlick(wo.z, float(k_of(p.roughness)));
    sum += glm::dvec3(F_SchlickSG(specular_F0(p.base_color, p.metalness), wo.z)) * double(G1 * G1);
  }
  return sum;
}

double brdf_pdf_integral(const BrdfParams& p, const glm::vec3& wo) {
  return test::integrate_grid<double>(
      lobe_grid(p, wo, 96), [&](const glm::vec3& wi) { return double(brdf_pdf(p, wo, wi)); }, 4);
}

// The probability that brdf_sample() rejects its sample, computed without brdf.cpp:
// a specular half vector h (pdf D NoH) reflects wo to wi with
//   wi.z = 2 (wo.h) h.z - wo.z = r cos(2 theta_h - delta),
// r = |(s, NoV)|, delta = atan2(s, NoV), s = the component of wo along h's azimuth; so for
// each azimuth the rejected theta_h (wi.z < kMinCosine) are |2 theta_h - delta| > acos(kMinCosine / r),
// whose probability follows from GGX's cdf in theta_h, tan^2 / (alpha^2 + tan^2). A cosine
// sample is rejected with probability kMinCosine^2.
double rejection_probability(const BrdfParams& p, const glm::vec3& wo) {
  const double ps = specular_probability(p, wo.z);
  const double diffuse_loss = (1.0 - ps) * double(kMinCosine) * kMinCosine;
  if (is_mirror(p.roughness)) return diffuse_loss;
  const double a2 = std::pow(double(p.roughness), 4.0);
  const auto cdf = [&](double theta) {
    if (theta <= 0.0) return 0.0;
    if (theta >= 0.5 * kPiD) return 1.0;
    const double t2 = std::pow(std::tan(theta), 2.0);
    return t2 / (a2 + t2);
  };
  constexpr int kSteps = 20000;
  double leak = 0.0;
  for (int i = 0; i < kSteps; ++i) {
    const double phi = (i + 0.5) * 2.0 * kPiD / kSteps;
    const double s = wo.x * std::cos(phi) + wo.y * std::sin(phi), c = wo.z;
    const double r = std::hypot(s, c), delta = std::atan2(s, c);
    const double a = std::acos(std::clamp(kMinCosine / r, -1.0, 1.0));
    leak += cdf(0.5 * (delta - a)) + (1.0 - cdf(0.5 * (delta + a)));
  }
  return ps * leak / kSteps + diffuse_loss;
}

struct McResult {
  glm::dvec3 mean{0.0}, std_error{0.0};
  double rejected = 0.0;  // fraction of samples brdf_sample() rejected
};

McResult albedo_monte_carlo(const BrdfParams& p, const glm::vec3& wo, int n, uint64_t seed) {
  Rng rng(seed, 17);
  glm::dvec3 sum(0.0), sum2(0.0);
  int rejected = 0;
  for (int i = 0; i < n; ++i) {
    const float u_lobe = rng.next_float();
    const glm::vec2 u = rng.next_2d();
    BrdfSample s;
    if (!brdf_sample(p, wo, u_lobe, u, &s)) {
      ++rejected;
      continue;
    }
    const glm::dvec3 w(s.weight);
    sum += w;
    sum2 += w * w;
  }
  McResult r;
  r.mean = sum / double(n);
  const glm::dvec3 var = glm::max(sum2 / double(n) - r.mean * r.mean, glm::dvec3(0.0));
  r.std_error = glm::sqrt(var / double(n));
  r.rejected = double(rejected) / n;
  return r;
}

// --- terms against hand-computed values ---------------------------------------------------

TEST(BrdfTerms, DGgx) {
  for (double alpha : {1.0, 0.25, 0.09, 0.0025}) {
    // NoH = 1: alpha^2 / (pi alpha^4) = 1 / (pi alpha^2).
    EXPECT_NEAR(D_GGX(1.0f, float(alpha)), 1.0 / (kPiD * alpha * alpha), 1e-5 / (alpha * alpha)) << alpha;
    // NoH -> 0+: alpha^2 / pi; at NoH = 0 exactly the chi+ cut-off (NoH must be > 0) gives 0.
    EXPECT_NEAR(D_GGX(1e-6f, float(alpha)), alpha * alpha / kPiD, 1e-6) << alpha;
    EXPECT_EQ(D_GGX(0.0f, float(alpha)), 0.0f);
  }
  // alpha = 1 is uniform in NoH: 1 / pi.
  EXPECT_NEAR(D_GGX(0.3f, 1.0f), 1.0 / kPiD, 1e-7);
  // NoH = cos(45 deg), alpha = 0.5: 0.25 / (pi (0.5 (0.25 - 1) + 1)^2) = 0.25 / (pi 0.390625).
  EXPECT_NEAR(D_GGX(float(std::sqrt(0.5)), 0.5f), 0.25 / (kPiD * 0.390625), 1e-6);
  EXPECT_EQ(D_GGX(-0.5f, 0.5f), 0.0f);
  // alpha = 0 is floored (at kMirrorRoughness^2), not 0/0.
  EXPECT_TRUE(std::isfinite(D_GGX(1.0f, 0.0f)));
  EXPECT_GT(D_GGX(1.0f, 0.0f), 0.0f);
}

TEST(BrdfTerms, FSchlickSG) {
  const glm::vec3 F0(0.04f, 0.5f, 1.0f);
  // VoH = 0: the exponent is 0, so F = F0 + (1 - F0) = 1 exactly.
  const glm::vec3 f0 = F_SchlickSG(F0, 0.0f);
  for (int c = 0; c < 3; ++c) EXPECT_FLOAT_EQ(f0[c], 1.0f);
  // VoH = 1: 2^(-5.55473 - 6.98316) = 2^-12.53789 = 1.6843e-4 remains (the SG fit is not
  // exact there), so F = F0 to within 1.7e-4.
  const double r1 = std::pow(2.0, -12.53789);
  const glm::vec3 f1 = F_SchlickSG(F0, 1.0f);
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(f1[c], F0[c] + (1.0 - F0[c]) * r1, 1e-6);
    EXPECT_NEAR(f1[c], F0[c], 1.7e-4);
  }
  // VoH = 0.5: exponent (-2.777365 - 6.98316) 0.5 = -4.8802625; 2^that = 0.0339543.
  const glm::vec3 fh = F_SchlickSG(glm::vec3(0.04f), 0.5f);
  EXPECT_NEAR(fh.x, 0.04 + 0.96 * std::pow(2.0, -4.8802625), 1e-6);
  EXPECT_NEAR(std::pow(2.0, -4.8802625), 0.0339543, 1e-6);
  // ... within 0.003 of Schlick's (1 - VoH)^5 = 0.03125 it approximates.
  EXPECT_NEAR(std::pow(2.0, -4.8802625), 0.03125, 3e-3);
  // Out-of-range VoH is clamped.
  EXPECT_FLOAT_EQ(F_SchlickSG(glm::vec3(0.04f), -0.2f).x, 1.0f);
}

TEST(BrdfTerms, SpecularF0) {
  const glm::vec3 B(1.0f, 0.5f, 0.0f);
  const glm::vec3 d = specular_F0(B, 0.0f), m = specular_F0(B, 1.0f), h = specular_F0(B, 0.5f);
  for (int c = 0; c < 3; ++c) {
    EXPECT_FLOAT_EQ(d[c], 0.04f);
    EXPECT_FLOAT_EQ(m[c], B[c]);
    EXPECT_FLOAT_EQ(h[c], 0.02f + 0.5f * B[c]);
  }
}

TEST(BrdfTerms, GSmithSchlick) {
  for (float R : {0.0f, 0.3f, 1.0f}) {
    EXPECT_FLOAT_EQ(G_SmithSchlick(1.0f, 1.0f, R), 1.0f) << R;
    EXPECT_FLOAT_EQ(G_SmithSchlick(0.0f, 1.0f, R), 0.0f) << R;
    EXPECT_FLOAT_EQ(G1_SmithSchlick(1.0f, float(k_of(R))), 1.0f) << R;
  }
  // R = 0: k = 1/8; G1(0.5) = 0.5 / (0.5 * 0.875 + 0.125) = 8/9.
  EXPECT_NEAR(G1_SmithSchlick(0.5f, 0.125f), 8.0 / 9.0, 1e-7);
  // R = 1: k = 1/2; G1(0.5) = 0.5 / 0.75 = 2/3; G = G1(0.5) G1(0.2) = 2/3 * 0.2/0.6.
  EXPECT_NEAR(G_SmithSchlick(0.5f, 0.2f, 1.0f), 2.0 / 3.0 * (0.2 / 0.6), 1e-7);
  // R = 0.3: k = 1.69/8 = 0.21125.
  EXPECT_NEAR(G_SmithSchlick(0.7f, 0.4f, 0.3f),
              0.7 / (0.7 * 0.78875 + 0.21125) * 0.4 / (0.4 * 0.78875 + 0.21125), 1e-6);
}

TEST(BrdfTerms, FdLambert) {
  const glm::vec3 f = Fd_Lambert(glm::vec3(0.8f, 0.4f, 0.0f), 0.25f);
  EXPECT_NEAR(f.x, 0.8 * 0.75 / kPiD, 1e-7);
  EXPECT_NEAR(f.y, 0.4 * 0.75 / kPiD, 1e-7);
  EXPECT_EQ(f.z, 0.0f);
  EXPECT_EQ(Fd_Lambert(glm::vec3(1.0f), 1.0f), glm::vec3(0.0f));
}

// --- eval ----------------------------------------------------------------------------------

TEST(BrdfEval, AssemblesEq14AtHandComputedPoints) {
  // wo = wi = n: h = n, D = 1/(pi alpha^2), F = F0 + (1-F0) 2^-12.53789, G = 1, so
  // f = B(1-M)/pi + D F / 4.
  const glm::vec3 B(0.8f, 0.4f, 0.2f);
  const BrdfParams p = params(0.5f, 0.5f, B);
  const glm::vec3 f = brdf_eval(p, glm::vec3(0, 0, 1), glm::vec3(0, 0, 1));
  const double alpha = 0.25, D = 1.0 / (kPiD * alpha * alpha), r1 = std::pow(2.0, -12.53789);
  for (int c = 0; c < 3; ++c) {
    const double F0 = 0.04 * 0.5 + 0.5 * B[c];
    const double expect = B[c] * 0.5 / kPiD + D * (F0 + (1.0 - F0) * r1) / 4.0;
    EXPECT_NEAR(f[c], expect, 1e-5 * expect) << c;
  }
  // wo at 60 deg, wi = n: h at 30 deg, so VoH = NoH = cos 30 deg differs from NoV = 0.5
  // (catches F or D evaluated at the wrong cosine). R = 0.6: alpha = 0.36, k = 0.32.
  {
    const glm::vec3 B2(0.3f, 0.6f, 0.9f);
    const BrdfParams q = params(0.6f, 0.3f, B2);
    const glm::vec3 f2 = brdf_eval(q, glm::vec3(std::sqrt(0.75f), 0.0f, 0.5f), glm::vec3(0, 0, 1));
    const double c30 = std::sqrt(0.75), a2 = 0.36 * 0.36, k = 1.6 * 1.6 / 8.0;
    const double D2 = a2 / (kPiD * std::pow(c30 * c30 * (a2 - 1.0) + 1.0, 2.0));
    const double G2 = 0.5 / (0.5 * (1.0 - k) + k);  // G1(1) = 1
    const double fc = std::pow(2.0, (-5.55473 * c30 - 6.98316) * c30);
    for (int c = 0; c < 3; ++c) {
      const double F0 = 0.04 * 0.7 + 0.3 * B2[c];
      const double expect = B2[c] * 0.7 / kPiD + D2 * (F0 + (1.0 - F0) * fc) * G2 / (4.0 * 0.5 * 1.0);
      EXPECT_NEAR(f2[c], expect, 1e-5 * expect) << c;
    }
  }
  // wo at 60 deg, wi at 60 deg on the opposite side: h = n, VoH = NoV = NoL = 0.5.
  const glm::vec3 wo(std::sqrt(0.75f), 0.0f, 0.5f), wi(-std::sqrt(0.75f), 0.0f, 0.5f);
  const BrdfParams q = params(1.0f, 1.0f, glm::vec3(1.0f));  // alpha = 1, k = 1/2, F0 = 1
  // D = 1/pi, F = 1, G = (0.5/0.75)^2 = 4/9: f = (1/pi)(4/9) / (4 * 0.25) = 4/(9 pi).
  EXPECT_NEAR(brdf_eval(q, wo, wi).x, 4.0 / (9.0 * kPiD), 1e-6);
}

TEST(BrdfEval, ZeroBelowTheSurface) {
  const BrdfParams p = params(0.3f, 0.5f, glm::vec3(0.7f));
  const glm::vec3 up = view_dir(0.7f), down(0.3f, 0.0f, -0.95393920f);
  EXPECT_EQ(brdf_eval(p, up, down), glm::vec3(0.0f));
  EXPECT_EQ(brdf_eval(p, down, up), glm::vec3(0.0f));
  EXPECT_EQ(brdf_pdf(p, up, down), 0.0f);
  EXPECT_EQ(brdf_pdf(p, down, up), 0.0f);
  // Within kMinCosine of the horizon counts as below.
  const glm::vec3 grazing(std::sqrt(1.0f - 0.25e-8f), 0.0f, 0.5e-4f);
  EXPECT_EQ(brdf_eval(p, up, grazing), glm::vec3(0.0f));
  BrdfSample s;
  EXPECT_FALSE(brdf_sample(p, down, 0.5f, glm::vec2(0.5f), &s));
  EXPECT_EQ(s.weight, glm::vec3(0.0f));
}

TEST(BrdfEval, Reciprocity) {
  Rng rng(41, 1);
  double worst = 0.0;
  for (int i = 0; i < 20000; ++i) {
    const BrdfParams p = params(rng.next_float(), rng.next_float(),
                                glm::vec3(rng.next_float(), rng.next_float(), rng.next_float()));
    const glm::vec3 a = sample_cosine_hemisphere(rng.next_2d());
    const glm::vec3 b = sample_cosine_hemisphere(rng.next_2d());
    const glm::vec3 fab = brdf_eval(p, a, b), fba = brdf_eval(p, b, a);
    for (int c = 0; c < 3; ++c) {
      const double rel = std::abs(double(fab[c]) - fba[c]) / std::max(1e-30, double(fab[c]));
      worst = std::max(worst, rel);
      ASSERT_NEAR(fab[c], fba[c], 1e-6f * fab[c]) << "R=" << p.roughness << " M=" << p.metalness;
    }
  }
  std::printf("[reciprocity] worst relative difference %.3g over 20000 pairs\n", worst);
}

// --- lobe choice and pdf -------------------------------------------------------------------

TEST(BrdfPdf, SpecularProbability) {
  for (float NoV : {1.0f, 0.5f, 0.01f}) {
    EXPECT_EQ(specular_probability(params(0.5f, 1.0f, glm::vec3(0.5f)), NoV), 1.0f);  // metal
    EXPECT_EQ(specular_probability(params(0.5f, 0.0f, glm::vec3(0.0f)), NoV), 1.0f);  // black
    for (float M : {0.0f, 0.5f, 0.99f}) {
      const float ps = specular_probability(params(0.5f, M, glm::vec3(0.8f)), NoV);
      EXPECT_GE(ps, 0.05f);
      EXPECT_LE(ps, 0.95f);
    }
  }
  // A white dielectric at normal view: F ~ 0.04 vs diffuse 1, so the 5% floor applies.
  EXPECT_FLOAT_EQ(specular_probability(params(0.5f, 0.0f), 1.0f), 0.05f);
  // At grazing view Fresnel grows and so does ps.
  EXPECT_GT(specular_probability(params(0.5f, 0.0f), 0.05f), 0.3f);
}

struct PdfCase {
  float R, M, NoV;
};

TEST(BrdfPdf, IntegratesToOneMinusTheSpecularLeak) {
  // The mixture pdf over the hemisphere equals 1 minus the probability that the sample is
  // rejected (a specular half vector reflecting wo below the horizon), which is computed
  // separately in half-vector space. The leak is reported for docs/brdf.md.
  std::printf("[pdf] R     M    NoV   integral   leak       sum-1\n");
  for (const PdfCase c : {PdfCase{0.05f, 0.0f, 1.0f}, PdfCase{0.05f, 1.0f, 0.5f}, PdfCase{0.05f, 1.0f, 0.05f},
                          PdfCase{0.3f, 0.0f, 1.0f}, PdfCase{0.3f, 0.5f, 0.5f}, PdfCase{0.3f, 1.0f, 0.5f},
                          PdfCase{0.3f, 1.0f, 0.1f}, PdfCase{0.3f, 1.0f, 0.02f}, PdfCase{0.6f, 1.0f, 0.5f},
                          PdfCase{1.0f, 0.0f, 1.0f}, PdfCase{1.0f, 1.0f, 1.0f}, PdfCase{1.0f, 1.0f, 0.5f},
                          PdfCase{1.0f, 0.5f, 0.1f}, PdfCase{1.0f, 1.0f, 0.02f}}) {
    const BrdfParams p = params(c.R, c.M, glm::vec3(0.8f));
    const glm::vec3 wo = view_dir(c.NoV);
    const double integral = brdf_pdf_integral(p, wo);
    const double leak = rejection_probability(p, wo);
    std::printf("[pdf] %.2f  %.1f  %.2f  %.6f   %.6f   %+.1e\n", c.R, c.M, c.NoV, integral, leak,
                integral + leak - 1.0);
    EXPECT_NEAR(integral + leak, 1.0, 1e-4) << "R=" << c.R << " M=" << c.M << " NoV=" << c.NoV;
    EXPECT_LE(leak, specular_probability(p, wo.z) + 1e-9);
    // Bounds for docs/brdf.md. Eq. 18 samples h from D NoH regardless of wo, so rough
    // lobes lose many samples: at R = 1 (alpha = 1, h cosine-distributed) and NoV = 1,
    // wi.z = 2 NoH^2 - 1 < 0 for half of them. Up to R = 0.3 and NoV >= 0.5 at most 3.1%.
    EXPECT_LE(leak, 0.5 * specular_probability(p, wo.z) + 2e-3) << "R=" << c.R << " NoV=" << c.NoV;
    if (c.NoV >= 0.5f && c.R <= 0.3f) {
      EXPECT_LE(leak, 0.031) << "R=" << c.R << " NoV=" << c.NoV;
    }
  }
}

TEST(BrdfPdf, MirrorBranchIntegratesToTheDiffuseShare) {
  for (float NoV : {1.0f, 0.5f, 0.05f}) {
    const BrdfParams p = params(0.0f, 0.5f, glm::vec3(0.8f));
    const glm::vec3 wo = view_dir(NoV);
    EXPECT_NEAR(brdf_pdf_integral(p, wo), 1.0 - specular_probability(p, NoV), 1e-3) << NoV;
  }
}

// --- chi-square: brdf_sample against brdf_pdf -----------------------------------------------

struct ChiCase {
  float R, M, NoV;
};

test::DirectionChiSquare brdf_chi_square(const ChiCase& c, uint64_t seed, int n) {
  const BrdfParams p = params(c.R, c.M, glm::vec3(0.9f, 0.6f, 0.3f));
  const glm::vec3 wo = view_dir(c.NoV);
  // (theta, phi) cells packed around the mirror direction; samples below the horizon
  // land outside the grid, in a cell of expected count 0.
  const LobeGrid grid = lobe_grid(p, wo, 32);
  Rng rng(seed, 23);
  return test::chi_square_directions(
      grid, n,
      [&](int, glm::vec3* wi, bool* delta) {
        const float u_lobe = rng.next_float();
        const glm::vec2 u = rng.next_2d();
        BrdfSample s;
        if (!brdf_sample(p, wo, u_lobe, u, &s)) return false;
        *wi = s.wi;
        *delta = s.delta;
        return true;
      },
      [&](const glm::vec3& wi) { return double(brdf_pdf(p, wo, wi)); }, 12,
      is_mirror(c.R) ? specular_probability(p, wo.z) : 0.0);
}

TEST(BrdfSampling, ChiSquare) {
  std::vector<ChiCase> cases;
  for (float R : {0.05f, 0.3f, 1.0f}) {
    for (float M : {0.0f, 0.5f, 1.0f}) {
      for (float NoV : {0.9f, 0.4f}) cases.push_back({R, M, NoV});
    }
  }
  // Grazing views, and the mirror branch (its delta samples form their own cell).
  for (const ChiCase c : {ChiCase{0.05f, 1.0f, 0.05f}, ChiCase{0.3f, 0.5f, 0.05f}, ChiCase{1.0f, 0.0f, 0.05f},
                          ChiCase{0.0f, 0.5f, 0.6f}})
    cases.push_back(c);
  constexpr int n = 400000;
  uint64_t seed = 1000;
  double p_min = 1.0, p_max = 0.0;
  for (const ChiCase& c : cases) {
    const auto r = brdf_chi_square(c, seed++, n);
    std::printf("[chi2] R=%.2f M=%.1f NoV=%.2f: %s\n", c.R, c.M, c.NoV, r.message.c_str());
    EXPECT_TRUE(r.passed(kSignificance)) << "R=" << c.R << " M=" << c.M << " NoV=" << c.NoV << ": "
                                         << r.message;
    // The rejection rate matches the pdf's missing mass: 5 binomial sigmas plus 1e-4 n for
    // the quadrature.
    const double q = std::max(r.rejected_expected / n, 0.0);
    EXPECT_NEAR(r.rejected_observed, r.rejected_expected, 5.0 * std::sqrt(n * q * (1 - q)) + 1e-4 * n)
        << "R=" << c.R << " M=" << c.M << " NoV=" << c.NoV;
    p_min = std::min(p_min, r.p_value);
    p_max = std::max(p_max, r.p_value);
  }
  std::printf("[chi2] %zu BRDF cases, p-values in [%.3g, %.3g]\n", cases.size(), p_min, p_max);
}

TEST(BrdfSampling, ChiSquareRejectsAWrongPdf) {
  // The same harness with the pdf's Jacobian 1/(4 VoH) dropped must fail, so the test
  // above can fail.
  const BrdfParams p = params(0.3f, 1.0f, glm::vec3(0.9f));
  const glm::vec3 wo = view_dir(0.4f);
  Rng rng(5, 23);
  const LobeGrid grid = lobe_grid(p, wo, 32);
  const auto r = test::chi_square_directions(
      grid, 200000,
      [&](int, glm::vec3* wi, bool*) {
        BrdfSample s;
        if (!brdf_sample(p, wo, rng.next_float(), rng.next_2d(), &s)) return false;
        *wi = s.wi;
        return true;
      },
      [&](const glm::vec3& wi) {
        if (wi.z < kMinCosine) return 0.0;
        const glm::vec3 h = glm::normalize(wo + wi);
        return double(D_GGX(h.z, 0.09f) * h.z);  // pdf_h, not the pdf of wi
      });
  EXPECT_FALSE(r.passed(kSignificance)) << r.message;
}

// --- sample weights ------------------------------------------------------------------------

TEST(BrdfSampling, WeightIsEvalCosOverPdf) {
  Rng rng(51, 3);
  int checked = 0, deltas = 0;
  for (int i = 0; i < 50000; ++i) {
    const float R = i % 7 == 0 ? 0.5f * kMirrorRoughness : rng.next_float();
    const BrdfParams p = params(R, rng.next_float(), glm::vec3(rng.next_float(), rng.next_float(), rng.next_float()));
    const glm::vec3 wo = sample_cosine_hemisphere(rng.next_2d());
    const float u_lobe = rng.next_float();
    const glm::vec2 u = rng.next_2d();
    BrdfSample s;
    if (!brdf_sample(p, wo, u_lobe, u, &s)) continue;
    ASSERT_GT(s.wi.z, 0.0f);
    ASSERT_NEAR(glm::length(s.wi), 1.0f, 1e-5f);
    if (s.delta) {
      // Mirror lobe: wi = (-wo.x, -wo.y, wo.z), weight = F(NoV) G1(NoV)^2 / ps, pdf = ps.
      ++deltas;
      ASSERT_TRUE(is_mirror(R));
      ASSERT_EQ(s.wi, mirror_of(wo));
      const float ps = specular_probability(p, wo.z);
      const float G1 = G1_SmithSchlick(wo.z, float(k_of(R)));
      const glm::vec3 expect = F_SchlickSG(specular_F0(p.base_color, p.metalness), wo.z) * G1 * G1 / ps;
      for (int c = 0; c < 3; ++c) ASSERT_NEAR(s.weight[c], expect[c], 1e-5f * expect[c] + 1e-7f);
      ASSERT_FLOAT_EQ(s.pdf, ps);
      continue;
    }
    ++checked;
    const float pdf = brdf_pdf(p, wo, s.wi);
    ASSERT_NEAR(s.pdf, pdf, 1e-5f * pdf) << "R=" << R;
    const glm::vec3 expect = brdf_eval(p, wo, s.wi) * s.wi.z / pdf;
    for (int c = 0; c < 3; ++c) ASSERT_NEAR(s.weight[c], expect[c], 1e-5f * expect[c] + 1e-9f) << "R=" << R;
  }
  EXPECT_GT(checked, 40000);
  EXPECT_GT(deltas, 1000);
}

struct FurnaceCase {
  float R, M, NoV;
};

TEST(BrdfSampling, WhiteFurnaceMatchesQuadrature) {
  // E[weight] is the directional albedo; compare with quadrature of eval * cos. Bound:
  // 4.5 standard errors of the mean plus 5e-4 for the quadrature.
  const glm::vec3 B(0.9f, 0.6f, 0.3f);
  constexpr int n = 100000;
  uint64_t seed = 7000;
  double worst_sigma = 0.0, min_se = 1e30, max_se = 0.0;
  std::string worst_case;
  for (float R : {0.0f, 0.05f, 0.3f, 0.6f, 1.0f}) {
    for (float M : {0.0f, 0.5f, 1.0f}) {
      for (float NoV : {1.0f, 0.5f, 0.1f}) {
        const BrdfParams p = params(R, M, B);
        const glm::vec3 wo = view_dir(NoV);
        const glm::dvec3 quad = albedo_quadrature(p, wo);
        const McResult mc = albedo_monte_carlo(p, wo, n, seed++);
        for (int c = 0; c < 3; ++c) {
          const double diff = std::abs(mc.mean[c] - quad[c]);
          if (mc.std_error[c] > 1e-6) min_se = std::min(min_se, mc.std_error[c]);
          max_se = std::max(max_se, mc.std_error[c]);
          // (Deterministic weights, e.g. a pure mirror, have no spread to compare with.)
          if (mc.std_error[c] > 1e-6 && diff / mc.std_error[c] > worst_sigma) {
            worst_sigma = diff / mc.std_error[c];
            char buf[200];
            std::snprintf(buf, sizeof buf, "R=%.2f M=%.1f NoV=%.1f channel %d: MC %.5f +- %.5f, quadrature %.5f", R,
                          M, NoV, c, mc.mean[c], mc.std_error[c], quad[c]);
            worst_case = buf;
          }
          EXPECT_LE(diff, 4.5 * mc.std_error[c] + 5e-4)
              << "R=" << R << " M=" << M << " NoV=" << NoV << " channel " << c << ": MC " << mc.mean[c]
              << " +- " << mc.std_error[c] << ", quadrature " << quad[c];
        }
      }
    }
  }
  std::printf("[furnace] 45 cases, standard errors in [%.1e, %.1e] (0 for pure mirrors), worst |MC - "
              "quadrature| = %.2f standard errors (%s)\n",
              min_se, max_se, worst_sigma, worst_case.c_str());
}

// --- energy --------------------------------------------------------------------------------

TEST(BrdfEnergy, MetalsNeverReflectMoreThanOne) {
  double worst = 0.0;
  for (float R : {0.0f, 0.008f, 0.01f, 0.02f, 0.05f, 0.1f, 0.2f, 0.3f, 0.4f, 0.5f, 0.6f, 0.7f, 0.8f, 0.9f, 1.0f}) {
    for (float NoV : {1.0f, 0.8f, 0.5f, 0.3f, 0.1f, 0.02f, 1e-3f}) {
      const double a = albedo_quadrature(params(R, 1.0f), view_dir(NoV), 64).x;
      worst = std::max(worst, a);
      EXPECT_LE(a, 1.0 + 1e-3) << "R=" << R << " NoV=" << NoV;
      EXPECT_GE(a, 0.0);
    }
  }
  std::printf("[energy] metal B=1: largest directional albedo %.4f\n", worst);
}

TEST(BrdfEnergy, RoughWhiteMetalMatchesClosedForm) {
  // R = 1, M = 1, B = 1, NoV = 1: D = 1/pi, F = 1, G1(NoV) = 1, G1(NoL) = 2 NoL / (1 + NoL)
  // (k = 1/2), so the albedo is (1/4pi) int 2 mu / (1 + mu) dOmega = 1 - ln 2 = 0.30685.
  // The model loses 69% of the energy here (no multiple scattering, and Schlick's G with
  // k = (R+1)^2/8 shadows more than Smith-GGX); rough metals render dark, as in the paper.
  const double expect = 1.0 - std::log(2.0);
  const BrdfParams p = params(1.0f, 1.0f);
  const glm::vec3 wo(0, 0, 1);
  EXPECT_NEAR(albedo_quadrature(p, wo).x, expect, 1e-4);
  const McResult mc = albedo_monte_carlo(p, wo, 200000, 77);
  EXPECT_NEAR(mc.mean.x, expect, 4.5 * mc.std_error.x);
}

TEST(BrdfEnergy, DielectricIsLambertPlusSpecular) {
  // With M = 0, F0 = 0.04 does not depend on B, so albedo(B) = B + albedo(B = 0): the
  // Lambert term integrates to B exactly (less the kMinCosine band, 1e-8) and the paper's
  // model has no (1 - F) on it. With B = 1 the total exceeds 1 by the specular albedo; we
  // keep that because the network's rendering layer uses the same BRDF (docs/brdf.md).
  for (float R : {0.0f, 0.05f, 0.3f, 1.0f}) {
    for (float NoV : {1.0f, 0.5f, 0.1f}) {
      const glm::vec3 wo = view_dir(NoV);
      const double specular = albedo_quadrature(params(R, 0.0f, glm::vec3(0.0f)), wo, 64).x;
      const double white = albedo_quadrature(params(R, 0.0f, glm::vec3(1.0f)), wo, 64).x;
      const double half = albedo_quadrature(params(R, 0.0f, glm::vec3(0.5f)), wo, 64).x;
      EXPECT_NEAR(white, 1.0 + specular, 1e-3) << "R=" << R << " NoV=" << NoV;
      EXPECT_NEAR(half, 0.5 + specular, 1e-3) << "R=" << R << " NoV=" << NoV;
      EXPECT_GT(specular, 0.0);
      EXPECT_GT(white, 1.0) << "R=" << R << " NoV=" << NoV;  // the documented excess
      EXPECT_LT(white, 1.25) << "R=" << R << " NoV=" << NoV;
    }
  }
  // The diffuse share is (1 - M) B for any M: with the mirror branch (R = 0) brdf_eval is
  // the Lambert term alone, so its integral of f cos is exactly that.
  for (float M : {0.0f, 0.5f, 0.9f}) {
    const glm::vec3 wo = view_dir(0.7f);
    const BrdfParams p = params(0.0f, M, glm::vec3(0.6f));
    const double diffuse = test::integrate_grid<double>(
        lobe_grid(p, wo), [&](const glm::vec3& wi) { return double(brdf_eval(p, wo, wi).x) * wi.z; }, 4);
    EXPECT_NEAR(diffuse, (1.0 - M) * 0.6, 1e-3) << "M=" << M;
  }
}

// --- mirror branch -------------------------------------------------------------------------

TEST(BrdfMirror, BranchIsTheLimitOfTheRoughLobe) {
  // (1) The limit: the rough lobe's albedo tends to the branch's F(NoV) G1(NoV, k)^2 (+ the
  //     Lambert B(1-M)) evaluated with the same k = (R+1)^2/8: within 0.1% for R <= 0.03.
  // (2) Continuity with R = 0: A(0.02..0.03) differs from A(0) only through k, which moves
  //     G1(NoV)^2 by 1.3% at NoV = 0.5 and 4% at NoV = 0.2 (R = 0.03): tolerances 1.5%
  //     at NoV >= 0.5, 4.5% at NoV = 0.2.
  // (3) Just below and just above kMirrorRoughness the sampled albedos agree (4.5 sigma).
  std::printf("[mirror] M    NoV   A(R=0)    A(0.01)   A(0.02)   A(0.03)   limit(0.03)\n");
  const glm::vec3 B(0.9f, 0.6f, 0.3f);
  for (float M : {0.0f, 1.0f}) {
    for (float NoV : {1.0f, 0.5f, 0.2f}) {
      const glm::vec3 wo = view_dir(NoV);
      const double a0 = albedo_quadrature(params(0.0f, M, B), wo).x;
      double a[3], limit[3];
      const float Rs[3] = {0.01f, 0.02f, 0.03f};
      for (int i = 0; i < 3; ++i) {
        a[i] = albedo_quadrature(params(Rs[i], M, B), wo).x;
        // The branch's formula at this R (is_mirror() is false here, so write it out).
        const float G1 = G1_SmithSchlick(NoV, float(k_of(Rs[i])));
        limit[i] = double(F_SchlickSG(specular_F0(B, M), NoV).x) * G1 * G1 + (1.0 - M) * B.x;
        EXPECT_NEAR(a[i], limit[i], 1e-3 * limit[i]) << "R=" << Rs[i] << " M=" << M << " NoV=" << NoV;
      }
      std::printf("[mirror] %.0f    %.1f   %.5f   %.5f   %.5f   %.5f   %.5f\n", M, NoV, a0, a[0], a[1], a[2],
                  limit[2]);
      const double tol = NoV >= 0.5f ? 1.5e-2 : 4.5e-2;
      EXPECT_NEAR(a[1], a0, tol * a0) << "M=" << M << " NoV=" << NoV;
      EXPECT_NEAR(a[2], a0, tol * a0) << "M=" << M << " NoV=" << NoV;
      const McResult below = albedo_monte_carlo(params(0.99f * kMirrorRoughness, M, B), wo, 50000, 3);
      const McResult above = albedo_monte_carlo(params(1.01f * kMirrorRoughness, M, B), wo, 50000, 4);
      EXPECT_NEAR(below.mean.x, above.mean.x, 4.5 * std::hypot(below.std_error.x, above.std_error.x) + 1e-3)
          << "M=" << M << " NoV=" << NoV;
    }
  }
}

// --- numerical sweep -----------------------------------------------------------------------

TEST(BrdfStability, FiniteAndNonNegativeEverywhere) {
  Rng rng(61, 9);
  int samples = 0, accepted = 0;
  for (float R : {0.0f, 1e-4f, kMirrorRoughness, 0.01f, 0.5f, 1.0f}) {
    for (float M : {0.0f, 1.0f}) {
      for (float Bv : {0.0f, 1.0f}) {
        const BrdfParams p = params(R, M, glm::vec3(Bv));
        for (float NoV : {1.0f, 1e-3f, 0.0f, -0.1f}) {
          const glm::vec3 wo = NoV >= 0.0f ? view_dir(NoV) : glm::normalize(glm::vec3(0.9f, 0.2f, NoV));
          const float ps = specular_probability(p, NoV);
          ASSERT_TRUE(std::isfinite(ps) && ps >= 0.0f && ps <= 1.0f);
          for (int i = 0; i < 2000; ++i) {
            // Random and extreme variates.
            float u_lobe = rng.next_float();
            glm::vec2 u = rng.next_2d();
            if (i < 9) {
              const float e[3] = {0.0f, 0.5f, 0x1.fffffep-1f};
              u_lobe = e[i % 3];
              u = glm::vec2(e[i / 3], e[(i + 1) % 3]);
            }
            BrdfSample s;
            const bool ok = brdf_sample(p, wo, u_lobe, u, &s);
            ++samples;
            ASSERT_TRUE(is_finite(s.weight) && is_finite(s.wi) && std::isfinite(s.pdf))
                << "R=" << R << " M=" << M << " B=" << Bv << " NoV=" << NoV;
            ASSERT_GE(std::min({s.weight.x, s.weight.y, s.weight.z}), 0.0f);
            ASSERT_GE(s.pdf, 0.0f);
            if (ok) {
              ++accepted;
              ASSERT_GT(s.pdf, 0.0f);
              ASSERT_GE(s.wi.z, kMinCosine);
            } else {
              ASSERT_EQ(s.weight, glm::vec3(0.0f));
            }
            // eval/pdf against arbitrary directions, including below and grazing.
            glm::vec3 wi = sample_uniform_sphere(rng.next_2d());
            if (i % 5 == 0) wi = glm::normalize(glm::vec3(wi.x, wi.y, 1e-5f * wi.z));
            const glm::vec3 f = brdf_eval(p, wo, wi);
            const float pdf = brdf_pdf(p, wo, wi);
            ASSERT_TRUE(is_finite(f) && std::isfinite(pdf));
            ASSERT_GE(std::min({f.x, f.y, f.z}), 0.0f);
            ASSERT_GE(pdf, 0.0f);
          }
        }
      }
    }
  }
  EXPECT_GT(accepted, samples / 3);
}

// --- the table in docs/brdf.md -------------------------------------------------------------

TEST(BrdfAlbedo, TableForDocs) {
  // Directional albedo (B = 1) by quadrature, with the sampled estimate beside it. The
  // assertions only guard the table's plausibility; the comparisons are the tests above.
  std::printf("| R | M | NoV | albedo (quadrature) | albedo (1e5 samples) | rejected samples |\n");
  std::printf("|---|---|---|---|---|---|\n");
  uint64_t seed = 9000;
  for (float R : {0.0f, 0.05f, 0.3f, 0.6f, 1.0f}) {
    for (float M : {0.0f, 0.5f, 1.0f}) {
      for (float NoV : {1.0f, 0.5f}) {
        const BrdfParams p = params(R, M);
        const glm::vec3 wo = view_dir(NoV);
        const double quad = albedo_quadrature(p, wo).x;
        const McResult mc = albedo_monte_carlo(p, wo, 100000, seed++);
        std::printf("| %.2f | %.1f | %.1f | %.4f | %.4f +- %.4f | %.2f%% |\n", R, M, NoV, quad, mc.mean.x,
                    mc.std_error.x, 100.0 * mc.rejected);
        EXPECT_GT(quad, 0.0);
        EXPECT_LT(quad, 1.25);
      }
    }
  }
}

// --- the specular lobe alone ----------------------------------------------------------------

TEST(BrdfSpecular, EvalIsTheBrdfLessItsLambertTerm) {
  for (float R : {0.0f, 0.02f, 0.3f, 1.0f})
    for (float M : {0.0f, 0.5f, 1.0f})
      for (float NoV : {1.0f, 0.5f, 0.05f})
        for (float NoL : {0.9f, 0.4f, 0.02f}) {
          const BrdfParams p = params(R, M, glm::vec3(0.8f));
          const glm::vec3 wo = view_dir(NoV), wi = view_dir(NoL, 2.9f);
          const glm::vec3 fs = specular_eval(p, wo, wi);
          const glm::vec3 fd = Fd_Lambert(p.base_color, p.metalness);
          ASSERT_GE(std::min({fs.x, fs.y, fs.z}), 0.0f);
          if (is_mirror(R)) {
            EXPECT_EQ(fs, glm::vec3(0.0f));
          }
          const glm::vec3 f = brdf_eval(p, wo, wi);
          for (int c = 0; c < 3; ++c) EXPECT_NEAR(fd[c] + fs[c], f[c], 1e-6f * f[c]) << "R=" << R << " M=" << M;
        }
}

TEST(BrdfSpecular, EvalIsPreciseWhereTheLobeIsTinyBesideTheDiffuseTerm) {
  // A narrow lobe seen far off its peak (back towards the viewer, 50 degrees from the
  // mirror direction): f_s is ~6e-8 of f_d, about an ulp of it, so f_r - f_d would be off by
  // tens of percent. The lobe alone matches eq. 14-17 evaluated in double.
  const BrdfParams p = params(0.02f, 0.0f, glm::vec3(0.8f));
  const glm::vec3 wo = view_dir(0.9f), wi = wo;
  const double alpha = double(0.02f) * double(0.02f), a2 = alpha * alpha;
  const glm::dvec3 h = glm::normalize(glm::dvec3(wo) + glm::dvec3(wi));
  const double D = a2 / (kPiD * std::pow(h.z * h.z * (a2 - 1.0) + 1.0, 2.0));
  const double VoH = glm::dot(glm::dvec3(wo), h), k = k_of(0.02f);
  const double F = 0.04 + 0.96 * std::exp2((-5.55473 * VoH - 6.98316) * VoH);
  const double G = wo.z / (wo.z * (1 - k) + k) * wi.z / (wi.z * (1 - k) + k);
  const double expected = D * F * G / (4.0 * wo.z * wi.z);
  ASSERT_LT(expected, 1e-7 * double(Fd_Lambert(p.base_color, 0.0f).x));
  EXPECT_NEAR(specular_eval(p, wo, wi).x, expected, 1e-3 * expected);
  // What the difference would give (so this test tells the two apart).
  const double difference = double(brdf_eval(p, wo, wi).x) - double(Fd_Lambert(p.base_color, 0.0f).x);
  EXPECT_GT(std::abs(difference - expected), 0.1 * expected);
}

TEST(BrdfSpecular, SampleAndPdfAgreeAndThePdfIntegratesToTheAcceptanceRate) {
  for (float R : {0.02f, 0.3f, 1.0f})
    for (float NoV : {0.9f, 0.3f, 0.05f}) {
      const BrdfParams p = params(R, 1.0f);
      const glm::vec3 wo = view_dir(NoV);
      Rng rng(77, 5);
      constexpr int n = 100000;
      int accepted = 0;
      for (int i = 0; i < n; ++i) {
        glm::vec3 wi;
        float pdf = 0.0f;
        if (!specular_sample(p, wo, rng.next_2d(), &wi, &pdf)) continue;
        ++accepted;
        ASSERT_EQ(pdf, specular_pdf(p, wo, wi));
      }
      const double integral = test::integrate_grid<double>(
          lobe_grid(p, wo, 96), [&](const glm::vec3& wi) { return double(specular_pdf(p, wo, wi)); }, 4);
      const double rate = double(accepted) / n;
      EXPECT_NEAR(integral, rate, 5.0 * std::sqrt(rate * (1.0 - rate) / n) + 1e-3) << "R=" << R << " NoV=" << NoV;
    }
}

TEST(BrdfSpecular, AlbedoTableMatchesQuadrature) {
  // The table is bilinear over 32 x 32 nodes: within 2% (and 1e-3) of the integral of f_s cos.
  for (float R : {0.05f, 0.3f, 0.7f, 1.0f})
    for (float M : {0.0f, 1.0f})
      for (float NoV : {1.0f, 0.5f, 0.15f}) {
        const BrdfParams p = params(R, M, glm::vec3(0.9f, 0.6f, 0.3f));
        const glm::vec3 wo = view_dir(NoV);
        const glm::dvec3 quad = test::integrate_grid<glm::dvec3>(
            lobe_grid(p, wo, 96), [&](const glm::vec3& wi) { return glm::dvec3(specular_eval(p, wo, wi)) * double(wi.z); },
            4);
        const glm::vec3 table = specular_albedo(p, NoV);
        for (int c = 0; c < 3; ++c)
          EXPECT_NEAR(table[c], quad[c], 0.02 * quad[c] + 1e-3) << "R=" << R << " M=" << M << " NoV=" << NoV;
      }
}

}  // namespace
}  // namespace phyir::render
