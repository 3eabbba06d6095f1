// The bench's lighting metrics (cli/bench/bench_probes_lighting.h) are eval's: a probe equal to the
// reference scores MAE 0 and SSIM 1; a probe k times too bright relights every sphere k times
// too bright (same seed, same sampling) and scores eval's closed-form SSIM of two constants;
// in input units the MAE scales and the SSIM is eval's on the scaled probes.
#include <gtest/gtest.h>

#include <cmath>

#include "bench_probes_lighting.h"
#include "phyir/core/error.h"

namespace phyir::cli {
namespace {

constexpr int kH = 8, kW = 16;  // texels per probe

// Probes side by side: probe k constant at constants[k], and (when `spot`) a bright texel
// above the horizon in each, which the mirror sphere reflects.
Image strip(const std::vector<float>& constants, bool spot) {
  Image out(kW * int(constants.size()), kH, 3);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < out.width; ++x)
      for (int c = 0; c < 3; ++c) out.at(x, y, c) = constants[size_t(x / kW)] * (1.0f + 0.1f * float(c));
  if (spot)
    for (size_t k = 0; k < constants.size(); ++k)
      for (int c = 0; c < 3; ++c) out.at(int(k) * kW + 5, 2, c) = 40.0f;
  return out;
}

Image scaled(Image image, float factor) {
  for (float& v : image.pixels) v *= factor;
  return image;
}

eval::RelightSettings quick() {
  eval::RelightSettings s;  // eval's materials and camera, fewer pixels and samples for speed
  s.size = 24;
  s.spp = 4;
  return s;
}

// eval's SSIM (C1 = 0.01^2) of two constant images a and b, on log(1 + L).
double constant_ssim(double a, double b) {
  const double x = std::log1p(a), y = std::log1p(b), c1 = 1e-4;
  return (2.0 * x * y + c1) / (x * x + y * y + c1);
}

}  // namespace

TEST(BenchProbesLighting, AProbeEqualToTheReferenceScoresPerfectly) {
  const Image reference = strip({1.0f, 0.3f}, true);
  const LitProbes a = light_probes(reference, kH, kW, quick());
  const LitProbes b = light_probes(reference, kH, kW, quick());
  const LightingMetrics m = lighting_metrics(a, b);
  EXPECT_EQ(m.probes, 2);
  for (size_t k = 0; k < kSphereMaterials; ++k) {
    EXPECT_EQ(m.mae[k], 0.0) << k;
    EXPECT_EQ(m.rmse[k], 0.0) << k;
    EXPECT_EQ(m.relative_mae[k], 0.0) << k;
  }
  EXPECT_NEAR(m.ssim, 1.0, 1e-9);
  ASSERT_EQ(m.probe_ssim.size(), 2u);
  EXPECT_NEAR(m.probe_ssim[1], 1.0, 1e-9);
}

TEST(BenchProbesLighting, TwentyPercentTooBrightIsTwentyPercentOnEverySphere) {
  const Image reference = strip({1.0f, 0.3f}, true);
  const LitProbes ref = light_probes(reference, kH, kW, quick());
  const LightingMetrics m = lighting_metrics(light_probes(scaled(reference, 1.2f), kH, kW, quick()), ref);
  for (size_t k = 0; k < kSphereMaterials; ++k) {
    EXPECT_NEAR(m.relative_mae[k], 0.2, 1e-4) << k;
    EXPECT_GT(m.mae[k], 0.0) << k;
    EXPECT_GE(m.rmse[k], m.mae[k]) << k;
  }
  EXPECT_LT(m.ssim, 0.999);
}

TEST(BenchProbesLighting, ConstantProbesScoreTheClosedFormSsim) {
  const Image reference = strip({1.0f, 3.0f}, false);
  Image measured = reference;
  for (int y = 0; y < kH; ++y)
    for (int x = kW; x < 2 * kW; ++x)
      for (int c = 0; c < 3; ++c) measured.at(x, y, c) *= 1.5f;  // the second probe only
  const LightingMetrics m =
      lighting_metrics(light_probes(measured, kH, kW, quick()), light_probes(reference, kH, kW, quick()));
  // SSIM per channel of constants (the channels are 1, 1.1, 1.2 times the probe's constant).
  double second = 0.0;
  for (int c = 0; c < 3; ++c) second += constant_ssim(3.0 * (1.0 + 0.1 * c) * 1.5, 3.0 * (1.0 + 0.1 * c)) / 3.0;
  ASSERT_EQ(m.probe_ssim.size(), 2u);
  EXPECT_NEAR(m.probe_ssim[0], 1.0, 1e-6);
  EXPECT_NEAR(m.probe_ssim[1], second, 1e-5);
  EXPECT_NEAR(m.ssim, (1.0 + second) / 2.0, 1e-5);
  // The first probe is exact; the pooled MAE is the mean of the probes' (equal sphere masks).
  for (size_t k = 0; k < kSphereMaterials; ++k) {
    EXPECT_EQ(m.probe_mae[0][k], 0.0);
    EXPECT_NEAR(m.mae[k], m.probe_mae[1][k] / 2.0, 1e-9);
  }
}

TEST(BenchProbesLighting, InputUnitsScaleTheMaeAndRecomputeTheSsim) {
  const Image reference = strip({1.0f, 3.0f}, false), measured = scaled(reference, 1.5f);
  const LitProbes a = light_probes(measured, kH, kW, quick()), b = light_probes(reference, kH, kW, quick());
  const LightingMetrics absolute = lighting_metrics(a, b);
  const LightingMetrics input = scaled_metrics(absolute, a, b, 4.0);
  // As eval would score probes four times as bright: relit again, the spheres are 4x.
  const LightingMetrics relit = lighting_metrics(light_probes(scaled(measured, 4.0f), kH, kW, quick()),
                                                 light_probes(scaled(reference, 4.0f), kH, kW, quick()));
  for (size_t k = 0; k < kSphereMaterials; ++k) {
    EXPECT_NEAR(input.mae[k], 4.0 * absolute.mae[k], 1e-9) << k;
    EXPECT_NEAR(input.mae[k], relit.mae[k], 1e-4 * relit.mae[k]) << k;
    EXPECT_DOUBLE_EQ(input.relative_mae[k], absolute.relative_mae[k]) << k;
  }
  double expected = 0.0;
  for (float probe : {1.0f, 3.0f})
    for (int c = 0; c < 3; ++c) {
      const double channel = 4.0 * probe * (1.0 + 0.1 * c);
      expected += constant_ssim(1.5 * channel, channel) / 6.0;
    }
  EXPECT_NEAR(input.ssim, expected, 1e-5);
  EXPECT_NEAR(input.ssim, relit.ssim, 1e-9);
  EXPECT_NE(input.ssim, absolute.ssim);
}

TEST(BenchProbesLighting, MismatchedStripsAreRefused) {
  EXPECT_THROW(light_probes(strip({1.0f}, false), kH, kW + 1, quick()), Error);
  const LitProbes one = light_probes(strip({1.0f}, false), kH, kW, quick());
  const LitProbes two = light_probes(strip({1.0f, 1.0f}, false), kH, kW, quick());
  EXPECT_THROW(lighting_metrics(one, two), Error);
}

}  // namespace phyir::cli
