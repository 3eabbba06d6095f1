// The toolkit's one auto-exposure rule (core/auto_exposure.h), as the dataset's input.png and
// phyir render's color.png use it.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "phyir/core/auto_exposure.h"

namespace phyir {
namespace {

TEST(AutoExposure, MapsThePercentileOfTheRgbValuesToTheTarget) {
  // 100 pixels of RGB (i, i, i) / 10 for i = 0..99: 300 values; the 95th percentile is the
  // value at index floor(0.95 * 300) = 285 of the sorted list, (285 / 3) / 10 = 9.5.
  Image image(10, 10, 3);
  for (int i = 0; i < 100; ++i)
    for (int c = 0; c < 3; ++c) image.pixels[size_t(i) * 3 + c] = float(i) / 10.0f;
  const AutoExposure e = auto_exposure(image, 0.95, 0.9);
  EXPECT_FLOAT_EQ(e.percentile_value, 9.5f);
  EXPECT_NEAR(e.stops, std::log2(0.9 / 9.5), 1e-6);
}

TEST(AutoExposure, ABlackOrBrokenImageGetsZeroStopsAndAnAbsurdOneIsClamped) {
  EXPECT_EQ(auto_exposure(Image(4, 2, 3)).stops, 0.0f);
  Image nan(1, 1, 3);
  for (float& v : nan.pixels) v = std::numeric_limits<float>::quiet_NaN();
  EXPECT_EQ(auto_exposure(nan, 0.5).stops, 0.0f);
  Image dim(1, 1, 3);
  for (float& v : dim.pixels) v = 1e-30f;
  EXPECT_EQ(auto_exposure(dim).stops, kMaxAutoExposureStops);
  EXPECT_EQ(auto_exposure(Image(0, 0, 3)).stops, 0.0f);
}

TEST(AutoExposure, OnlyTheFirstThreeChannelsCount) {
  Image rgba(1, 1, 4);
  rgba.pixels = {0.45f, 0.45f, 0.45f, 1000.0f};
  EXPECT_NEAR(auto_exposure(rgba, 1.0, 0.9).stops, 1.0f, 1e-6);
}

}  // namespace
}  // namespace phyir
