// probe_calibration: on synthetic errors of known spread it reports 1 and 95.4% when the
// stated standard error is right, and scales with a wrong one.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "phyir/core/error.h"
#include "phyir/render/probe_calibration.h"

namespace phyir::render {
namespace {

// A grey reference of 0.5, values = reference + N(0, sigma) in every channel (so the
// luminance error is N(0, sigma)); stated standard errors `stated` on the value, 0 on the reference.
ProbeCalibration calibration_of(double sigma, double stated) {
  const int w = 200, h = 100;
  Image value(w, h, 3), reference(w, h, 3, 0.5f), value_se(w, h, 1, float(stated)), reference_se(w, h, 1, 0.0f);
  std::mt19937 rng(7);
  std::normal_distribution<double> noise(0.0, sigma);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const float e = float(noise(rng));
      for (int c = 0; c < 3; ++c) value.at(x, y, c) = 0.5f + e;
    }
  return probe_calibration(value, value_se, reference, reference_se);
}

}  // namespace

TEST(ProbeCalibration, GaussianErrorsWithTheRightSigmaScoreOne) {
  const ProbeCalibration c = calibration_of(0.01, 0.01);
  EXPECT_EQ(c.texels, 20000u);
  EXPECT_NEAR(c.median_ratio, 1.0, 0.03);
  EXPECT_NEAR(c.within_two_sigma, 0.954, 0.01);
}

TEST(ProbeCalibration, AnUnderstatedSigmaScoresAboveOne) {
  const ProbeCalibration c = calibration_of(0.02, 0.01);
  EXPECT_NEAR(c.median_ratio, 2.0, 0.06);
  EXPECT_NEAR(c.within_two_sigma, 0.683, 0.015);  // |e| <= 1 true sigma
}

TEST(ProbeCalibration, BlackTexelsAreLeftOutAndSizesChecked) {
  const Image black(4, 2, 3, 0.0f), zero(4, 2, 1, 0.0f);
  const ProbeCalibration c = probe_calibration(black, zero, black, zero);
  EXPECT_EQ(c.texels, 0u);
  EXPECT_TRUE(std::isnan(c.median_ratio));
  EXPECT_TRUE(c.to_json()["median_ratio"].is_null());
  EXPECT_THROW(probe_calibration(black, Image(3, 2, 1), black, zero), Error);
}

}  // namespace phyir::render
