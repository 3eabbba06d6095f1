// Colour management through the shipped OpenColorIO config, checked against the sRGB
// transfer function (IEC 61966-2-1) written out independently here.
#include <gtest/gtest.h>

#include <cmath>

#include "phyir/core/colour.h"

namespace {

float srgb_decode_reference(float v) {
  return v <= 0.04045f ? v / 12.92f : std::pow((v + 0.055f) / 1.055f, 2.4f);
}

}  // namespace

TEST(Colour, SrgbDecodeMatchesTheStandardCurve) {
  phyir::Image image(6, 1, 4);
  const float values[6] = {0.0f, 0.02f, 0.04045f, 0.2f, 0.5f, 1.0f};
  for (int x = 0; x < 6; ++x) {
    for (int c = 0; c < 3; ++c) image.at(x, 0, c) = values[x];
    image.at(x, 0, 3) = 0.5f;
  }
  phyir::srgb_to_linear(image);
  for (int x = 0; x < 6; ++x) {
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(image.at(x, 0, c), srgb_decode_reference(values[x]), 2e-5f) << x;
    EXPECT_FLOAT_EQ(image.at(x, 0, 3), 0.5f) << "alpha must not be converted";
  }
}

TEST(Colour, DisplayTransformInvertsTheDecodeAndAppliesExposure) {
  phyir::Image linear(3, 1, 3);
  const float values[3] = {0.0f, 0.18f, 0.5f};
  for (int x = 0; x < 3; ++x)
    for (int c = 0; c < 3; ++c) linear.at(x, 0, c) = values[x];
  const phyir::Image display = phyir::linear_to_display(linear, 1.0f);  // +1 stop doubles
  for (int x = 0; x < 3; ++x)
    EXPECT_NEAR(srgb_decode_reference(display.at(x, 0, 0)), std::min(1.0f, 2.0f * values[x]), 1e-4f) << x;
}

TEST(Colour, DisplayClipsHighlights) {
  phyir::Image linear(1, 1, 3, 50.0f);
  const phyir::Image display = phyir::linear_to_display(linear, 0.0f);
  EXPECT_NEAR(display.at(0, 0, 0), 1.0f, 1e-5f);
}
