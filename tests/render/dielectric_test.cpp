// The smooth dielectric (render/src/dielectric.cpp): exact unpolarised Fresnel checked
// against the closed forms and the angle (Fresnel's sine/tangent) formulas, total
// internal reflection, Snell's law for the refracted direction, and the lobe choice
// (reflect with probability F, weights 1 and tint, so the expected throughput of a
// white dielectric is exactly 1).
#include <gtest/gtest.h>

#include <cmath>

#include "phyir/core/safe_math.h"
#include "phyir/render/dielectric.h"

namespace phyir::render {
namespace {

glm::vec3 dir_at(double theta, double phi = 0.7) {
  return glm::vec3(float(std::sin(theta) * std::cos(phi)), float(std::sin(theta) * std::sin(phi)),
                   float(std::cos(theta)));
}

// Fresnel's equations in angle form (Born & Wolf 1.5.3), independent of the cosine form
// used in dielectric.cpp: Rs = sin^2(ti - tt) / sin^2(ti + tt), Rp = tan^2(...) / tan^2(...).
double fresnel_angles(double theta_i, double eta) {
  const double theta_t = std::asin(std::sin(theta_i) / eta);
  const double rs = std::pow(std::sin(theta_i - theta_t) / std::sin(theta_i + theta_t), 2);
  const double rp = std::pow(std::tan(theta_i - theta_t) / std::tan(theta_i + theta_t), 2);
  return 0.5 * (rs + rp);
}

TEST(DielectricFresnel, NormalIncidence) {
  for (float eta : {1.33f, 1.5f, 2.42f, 1.0f / 1.5f, 1.0f}) {
    const double r = (eta - 1.0) / (eta + 1.0);
    EXPECT_NEAR(fresnel_dielectric(1.0f, eta), r * r, 1e-7) << eta;
  }
  EXPECT_NEAR(fresnel_dielectric(1.0f, 1.5f), 0.04, 1e-7);  // the 4% of glass
  EXPECT_NEAR(fresnel_dielectric(0.3f, 1.0f), 0.0f, 1e-12f);  // no interface
}

TEST(DielectricFresnel, MatchesTheAngleForm) {
  for (double eta : {1.33, 1.5, 2.0}) {
    for (double deg = 1.0; deg < 89.5; deg += 2.0) {
      const double theta = deg * 3.14159265358979323846 / 180.0;
      EXPECT_NEAR(fresnel_dielectric(float(std::cos(theta)), float(eta)), fresnel_angles(theta, eta), 2e-6)
          << "eta=" << eta << " theta=" << deg;
    }
  }
  // Grazing incidence reflects everything.
  EXPECT_NEAR(fresnel_dielectric(0.0f, 1.5f), 1.0f, 1e-6f);
}

TEST(DielectricFresnel, SymmetricAcrossTheInterface) {
  // Light crossing one way or the other at corresponding angles sees the same F (to float
  // precision: F is steep near grazing, 5e-6 apart at 87 deg).
  for (double deg = 0.0; deg < 89.0; deg += 3.0) {
    const double ti = deg * 3.14159265358979323846 / 180.0;
    const double tt = std::asin(std::sin(ti) / 1.5);
    EXPECT_NEAR(fresnel_dielectric(float(std::cos(ti)), 1.5f), fresnel_dielectric(float(std::cos(tt)), 1.0f / 1.5f),
                1e-5)
        << deg;
  }
  // A negative cosine swaps the media (pbrt convention).
  EXPECT_FLOAT_EQ(fresnel_dielectric(-0.6f, 1.5f), fresnel_dielectric(0.6f, 1.0f / 1.5f));
}

TEST(DielectricFresnel, TotalInternalReflection) {
  // Leaving glass (eta = 1/1.5): critical angle asin(1/1.5) = 41.81 deg.
  const double critical = std::asin(1.0 / 1.5);
  EXPECT_EQ(fresnel_dielectric(float(std::cos(critical + 1e-3)), 1.0f / 1.5f), 1.0f);
  EXPECT_EQ(fresnel_dielectric(float(std::cos(1.2)), 1.0f / 1.5f), 1.0f);
  EXPECT_LT(fresnel_dielectric(float(std::cos(critical - 1e-2)), 1.0f / 1.5f), 1.0f);
  // Approaching from below the critical angle F rises continuously towards 1.
  EXPECT_GT(fresnel_dielectric(float(std::cos(critical - 1e-4)), 1.0f / 1.5f), 0.9f);
  // The sampler always reflects then, with weight 1.
  const glm::vec3 wo = dir_at(critical + 0.05);
  for (float u : {0.0f, 0.5f, 0x1.fffffep-1f}) {
    const DielectricSample s = sample_dielectric(wo, 1.5f, /*entering=*/false, glm::vec3(0.5f), u);
    EXPECT_FALSE(s.transmitted);
    EXPECT_EQ(s.weight, glm::vec3(1.0f));
    EXPECT_EQ(s.wi, glm::vec3(-wo.x, -wo.y, wo.z));
  }
}

TEST(DielectricSampling, RefractionObeysSnell) {
  for (bool entering : {true, false}) {
    const double eta_rel = entering ? 1.5 : 1.0 / 1.5;  // n_t / n_i
    for (double deg = 0.0; deg < 89.0; deg += 4.0) {
      const glm::vec3 wo = dir_at(deg * 3.14159265358979323846 / 180.0);
      const DielectricSample s = sample_dielectric(wo, 1.5f, entering, glm::vec3(1.0f), 0x1.fffffep-1f);
      const float F = fresnel_dielectric(wo.z, float(eta_rel));
      if (F >= 1.0f) {
        EXPECT_FALSE(s.transmitted);
        continue;
      }
      ASSERT_TRUE(s.transmitted) << deg;
      EXPECT_LT(s.wi.z, 0.0f);
      EXPECT_NEAR(glm::length(s.wi), 1.0f, 1e-6f);
      // n_i sin(theta_i) = n_t sin(theta_t).
      const double sin_i = std::hypot(wo.x, wo.y), sin_t = std::hypot(s.wi.x, s.wi.y);
      EXPECT_NEAR(sin_i, eta_rel * sin_t, 2e-6) << "entering=" << entering << " theta=" << deg;
      // In the plane of incidence, on the far side of the normal.
      EXPECT_NEAR(wo.x * s.wi.y - wo.y * s.wi.x, 0.0f, 1e-6f);
      EXPECT_LE(wo.x * s.wi.x + wo.y * s.wi.y, 1e-7f);
    }
  }
  // Normal incidence goes straight through.
  const DielectricSample s = sample_dielectric(glm::vec3(0, 0, 1), 1.5f, true, glm::vec3(1.0f), 0.9f);
  EXPECT_TRUE(s.transmitted);
  EXPECT_NEAR(s.wi.z, -1.0f, 1e-7f);
}

TEST(DielectricSampling, ReflectsWithProbabilityFresnelAndConservesEnergy) {
  // Stratified u: the reflected fraction is F to within 1/n, the refracted one 1 - F, and
  // with weights 1 and tint the expected throughput is F + (1 - F) tint (= 1 for white).
  constexpr int n = 100000;
  const glm::vec3 tint(0.9f, 0.5f, 0.2f);
  for (bool entering : {true, false}) {
    for (double deg : {0.0, 30.0, 41.0, 60.0, 85.0}) {
      const glm::vec3 wo = dir_at(deg * 3.14159265358979323846 / 180.0);
      const float F = fresnel_dielectric(wo.z, entering ? 1.5f : 1.0f / 1.5f);
      int reflected = 0;
      glm::dvec3 throughput(0.0), white(0.0);
      for (int i = 0; i < n; ++i) {
        const float u = (i + 0.5f) / n;
        const DielectricSample s = sample_dielectric(wo, 1.5f, entering, tint, u);
        const DielectricSample w = sample_dielectric(wo, 1.5f, entering, glm::vec3(1.0f), u);
        ASSERT_EQ(s.transmitted, w.transmitted);
        if (!s.transmitted) {
          ++reflected;
          ASSERT_EQ(s.weight, glm::vec3(1.0f));
          ASSERT_GT(s.wi.z, 0.0f);
        } else {
          ASSERT_EQ(s.weight, tint);
        }
        throughput += glm::dvec3(s.weight);
        white += glm::dvec3(w.weight);
      }
      const double pr = double(reflected) / n, pt = 1.0 - pr;
      EXPECT_NEAR(pr, F, 2.0 / n) << "entering=" << entering << " theta=" << deg;
      EXPECT_NEAR(pr + pt, 1.0, 1e-12);
      for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(throughput[c] / n, F + (1.0 - F) * tint[c], 3.0 / n);
        EXPECT_NEAR(white[c] / n, 1.0, 1e-12);
      }
    }
  }
}

TEST(DielectricSampling, FiniteForDegenerateInput) {
  for (float eta : {1.0f, 1.5f, 0.0f, -1.0f, INFINITY, NAN}) {
    for (float z : {0.0f, 1e-8f, 0.5f, 1.0f}) {
      for (bool entering : {true, false}) {
        for (float u : {0.0f, 0.5f, 0x1.fffffep-1f}) {
          const glm::vec3 wo = glm::normalize(glm::vec3(std::sqrt(1.0f - z * z), 0.0f, z + 1e-30f));
          const DielectricSample s = sample_dielectric(wo, eta, entering, glm::vec3(1.0f), u);
          ASSERT_TRUE(is_finite(s.wi) && is_finite(s.weight)) << eta << " " << z;
          ASSERT_NEAR(glm::length(s.wi), 1.0f, 1e-5f);
          ASSERT_TRUE(std::isfinite(fresnel_dielectric(z, eta)));
        }
      }
    }
  }
}

}  // namespace
}  // namespace phyir::render
