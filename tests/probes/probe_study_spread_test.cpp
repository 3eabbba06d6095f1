// probe_study_spread: each probe's relative RMSE on strips of known per-probe errors, and the
// median and 90th percentile by numpy's linear interpolation.
#include <gtest/gtest.h>

#include <cmath>

#include "phyir/core/error.h"
#include "phyir/render/probe_study_spread.h"

namespace phyir::render {
namespace {

constexpr int kRes = 4;  // probes 4 x 4 texels

// Probes side by side, probe k constant at values[k] in every channel.
Image strip(const std::vector<float>& values) {
  Image out(kRes * int(values.size()), kRes, 3);
  for (int y = 0; y < kRes; ++y)
    for (int x = 0; x < out.width; ++x)
      for (int c = 0; c < 3; ++c) out.at(x, y, c) = values[size_t(x / kRes)];
  return out;
}

}  // namespace

TEST(ProbeStudySpread, QuantileInterpolatesBetweenOrderStatistics) {
  const std::vector<double> v = {10, 1, 9, 2, 8, 3, 7, 4, 6, 5};  // 1..10, unsorted
  EXPECT_DOUBLE_EQ(quantile(v, 0.5), 5.5);
  EXPECT_DOUBLE_EQ(quantile(v, 0.9), 9.1);  // position 8.1: 9 + 0.1 (10 - 9)
  EXPECT_DOUBLE_EQ(quantile(v, 0.0), 1.0);
  EXPECT_DOUBLE_EQ(quantile(v, 1.0), 10.0);
  EXPECT_DOUBLE_EQ(quantile({3.0}, 0.9), 3.0);
  EXPECT_TRUE(std::isnan(quantile({}, 0.5)));
}

TEST(ProbeStudySpread, EachProbeIsRelativeToItsOwnMean) {
  // References 1, 2, 4, 0.5; errors 0.1, 0.4, 0, 0.5 => 10%, 20%, 0%, 100%.
  const Image reference = strip({1.0f, 2.0f, 4.0f, 0.5f});
  const Image measured = strip({1.1f, 2.4f, 4.0f, 1.0f});
  const std::vector<double> e = per_probe_relative_rmse(measured, reference, reference, kRes);
  ASSERT_EQ(e.size(), 4u);
  EXPECT_NEAR(e[0], 0.1, 1e-6);
  EXPECT_NEAR(e[1], 0.2, 1e-6);
  EXPECT_NEAR(e[2], 0.0, 1e-12);
  EXPECT_NEAR(e[3], 1.0, 1e-6);
  // Half of the halves' difference, relative to the mean, as the reference's own noise.
  const std::vector<double> half = per_probe_relative_rmse(measured, reference, reference, kRes, 0.5);
  EXPECT_NEAR(half[1], 0.1, 1e-6);

  const ProbeSpread s = probe_spread(e);
  EXPECT_NEAR(s.median, 0.15, 1e-6);                  // between 10% and 20%
  EXPECT_NEAR(s.p90, 0.2 + 0.7 * (1.0 - 0.2), 1e-6);  // position 2.7 of 0, 0.1, 0.2, 1
  EXPECT_EQ(s.relative_rmse.size(), 4u);
}

TEST(ProbeStudySpread, OneBadProbeMovesTheP90NotTheMedian) {
  std::vector<float> ref(20, 1.0f), measured(20, 1.05f);
  measured[7] = 3.0f;  // one probe 200% off
  const ProbeSpread s = probe_spread(per_probe_relative_rmse(strip(measured), strip(ref), strip(ref), kRes));
  EXPECT_NEAR(s.median, 0.05, 1e-6);
  EXPECT_NEAR(s.p90, 0.05, 1e-6);  // 1 in 20 is beyond the 90th percentile
  measured[3] = 3.0f;  // 2 in 20: position 17.1 of 18 x 5%, 2 x 200% interpolates
  const ProbeSpread t = probe_spread(per_probe_relative_rmse(strip(measured), strip(ref), strip(ref), kRes));
  EXPECT_NEAR(t.median, 0.05, 1e-6);
  EXPECT_NEAR(t.p90, 0.05 + 0.1 * (2.0 - 0.05), 1e-5);
  measured[11] = 3.0f;  // 3 in 20: the 90th percentile is a bad probe
  EXPECT_NEAR(probe_spread(per_probe_relative_rmse(strip(measured), strip(ref), strip(ref), kRes)).p90, 2.0, 1e-5);
}

TEST(ProbeStudySpread, ADarkProbeScoresZeroAndBadStripsThrow) {
  const Image zero = strip({0.0f}), one = strip({1.0f});
  EXPECT_EQ(per_probe_relative_rmse(one, zero, zero, kRes)[0], 0.0);
  EXPECT_THROW(per_probe_relative_rmse(strip({1.0f, 1.0f}), one, one, kRes), Error);
  EXPECT_THROW(per_probe_relative_rmse(one, one, one, 3), Error);
}

}  // namespace phyir::render
