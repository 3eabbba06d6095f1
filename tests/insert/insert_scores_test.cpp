// The bench's scores: masked RMSE and SSIM see only their region, SSIM matches its closed form
// on flat images, the temporal score compares changes (not levels), summaries skip NaNs.
#include <gtest/gtest.h>

#include <cmath>

#include "phyir/core/error.h"
#include "phyir/insert/insert_scores.h"

namespace phyir::insert {
namespace {

Image flat(int w, int h, float v) {
  Image i(w, h, 3);
  for (float& p : i.pixels) p = v;
  return i;
}

// A 4 x 4 square of ones at (x0, y0) in a 32 x 16 mask.
Image square_region(int x0, int y0) {
  Image r(32, 16, 1);
  for (int y = y0; y < y0 + 4; ++y)
    for (int x = x0; x < x0 + 4; ++x) r.at(x, y, 0) = 1.0f;
  return r;
}

TEST(InsertScores, RmseCountsOnlyTheRegion) {
  Image a = flat(32, 16, 0.5f), b = flat(32, 16, 0.5f);
  const Image region = square_region(10, 6);
  b.at(0, 0, 0) = 100.0f;  // outside
  EXPECT_EQ(masked_rmse(a, b, region), 0.0);
  b.at(11, 7, 1) = 0.5f + 0.48f;  // one of 16 x 3 values inside, off by 0.48
  EXPECT_NEAR(masked_rmse(a, b, region), std::sqrt(0.48 * 0.48 / 48.0), 1e-6);
}

TEST(InsertScores, SsimIsOneForEqualImagesAndItsClosedFormOnFlatOnes) {
  const Image region = square_region(10, 6);
  EXPECT_NEAR(masked_ssim(flat(32, 16, 0.3f), flat(32, 16, 0.3f), region), 1.0, 1e-12);
  // Flat images: no variance, so SSIM = (2 a b + C1) / (a^2 + b^2 + C1).
  const double a = 0.3, b = 0.5, c1 = 1e-4;
  EXPECT_NEAR(masked_ssim(flat(32, 16, 0.3f), flat(32, 16, 0.5f), region),
              (2 * a * b + c1) / (a * a + b * b + c1), 1e-6);
}

TEST(InsertScores, SsimIgnoresChangesBeyondTheWindowAndSeesThoseInside) {
  Image a(32, 16, 3), b(32, 16, 3);
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 32; ++x)
      for (int c = 0; c < 3; ++c) a.at(x, y, c) = b.at(x, y, c) = 0.1f + 0.02f * float((x * 7 + y * 3 + c) % 11);
  const Image region = square_region(10, 6);
  b.at(20, 2, 0) = 0.9f;  // 6 columns from the region: beyond the radius-2 window
  EXPECT_NEAR(masked_ssim(a, b, region), 1.0, 1e-12);
  b.at(12, 8, 0) = 0.9f;  // inside
  EXPECT_LT(masked_ssim(a, b, region), 0.99);
}

TEST(InsertScores, SsimWrapsRoundThePanorama) {
  Image a = flat(32, 16, 0.4f), b = flat(32, 16, 0.4f);
  b.at(31, 7, 0) = 0.9f;  // the last column is the first one's neighbour
  EXPECT_LT(masked_ssim(a, b, square_region(0, 6)), 1.0 - 1e-6);
}

TEST(InsertScores, EmptyRegionIsNanAndMismatchedSizesAreAnError) {
  EXPECT_TRUE(std::isnan(masked_rmse(flat(8, 4, 1), flat(8, 4, 1), Image(8, 4, 1))));
  EXPECT_TRUE(std::isnan(masked_ssim(flat(8, 4, 1), flat(8, 4, 1), Image(8, 4, 1))));
  EXPECT_THROW(masked_rmse(flat(8, 4, 1), flat(8, 5, 1), Image(8, 4, 1)), Error);
  EXPECT_THROW(masked_ssim(flat(8, 4, 1), flat(8, 4, 1), Image(4, 4, 1)), Error);
}

TEST(InsertScores, ChangeErrorComparesChangesNotLevels) {
  const std::vector<glm::dvec3> truth = {glm::dvec3(1.0), glm::dvec3(1.1), glm::dvec3(1.2)};
  // A constant offset (a biased but steady composite) changes as the truth does.
  const std::vector<glm::dvec3> offset = {glm::dvec3(2.0), glm::dvec3(2.1), glm::dvec3(2.2)};
  EXPECT_NEAR(change_error(offset, truth), 0.0, 1e-12);
  // A flickering one: +0.3 then -0.3 where the truth rose 0.1 each step.
  const std::vector<glm::dvec3> flicker = {glm::dvec3(1.0), glm::dvec3(1.3), glm::dvec3(1.0)};
  EXPECT_NEAR(change_error(flicker, truth), std::sqrt((0.2 * 0.2 + 0.4 * 0.4) / 2.0), 1e-12);
  EXPECT_NEAR(rms_change(truth), 0.1, 1e-12);
  EXPECT_THROW(change_error(truth, {glm::dvec3(1.0)}), Error);
}

TEST(InsertScores, SummaryIsMeanAndSampleDeviationWithoutNans) {
  const ScoreSummary s = summarize({1.0, 3.0, std::nan("")});
  EXPECT_EQ(s.count, 2);
  EXPECT_DOUBLE_EQ(s.mean, 2.0);
  EXPECT_NEAR(s.sd, std::sqrt(2.0), 1e-12);
  EXPECT_EQ(summarize({5.0}).sd, 0.0);
  EXPECT_TRUE(std::isnan(summarize({}).mean));
}

}  // namespace
}  // namespace phyir::insert
