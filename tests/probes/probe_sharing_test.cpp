// Sharing between neighbouring probes (probe_sharing.h): the interleaved strata cover every
// sub-cell once per window and stay uniform alone; the weighted average takes exactly the
// neighbours on the same surface whose texel parallax is small, and nothing else.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "probe_sharing.h"
#include "phyir/render/rng.h"

namespace phyir::render {
namespace {

TEST(ProbeInterleave, AFullWindowCoversEverySubCellOfEveryCellOnce) {
  const ProbeSharing sharing;  // radius 1: 3 x 3 windows
  const int n = sharing.window();
  for (uint64_t key : {1ull, 77ull, 123456789ull}) {
    // 4 points per call on a 2 x 2 grid, each cell split 3 x 3: 36 sub-cells of side 1/6.
    std::vector<int> hits(36, 0);
    for (int i = 5; i < 5 + n; ++i) {      // any window: rows 5..7, columns 11..13
      for (int j = 11; j < 11 + n; ++j) {
        Rng rng(uint64_t(i * 100 + j), 3);  // each probe permutes cells its own way
        Interleave interleave{sub_stratum(i, j, sharing), n, key};
        std::vector<glm::vec2> points;
        stratified_square(4, rng, &points, interleave);
        for (const glm::vec2& p : points) {
          ASSERT_TRUE(p.x >= 0 && p.x < 1 && p.y >= 0 && p.y < 1);
          ++hits[int(p.y * 6) * 6 + int(p.x * 6)];
        }
      }
    }
    for (int k = 0; k < 36; ++k) EXPECT_EQ(hits[k], 1) << "key " << key << " sub-cell " << k;
  }
}

TEST(ProbeInterleave, OneProbeAloneIsUniformOverItsCells) {
  // Over many keys the sub-cell one probe draws in is uniform: chi-square on the 3 x 3
  // sub-cells of a single cell for sub (1, 2), 9000 draws (8 degrees of freedom: 99.9% below 26.1).
  const int n = 3, draws = 9000;
  std::vector<int> hits(9, 0);
  for (int k = 0; k < draws; ++k) {
    Rng rng(uint64_t(k), 1);
    std::vector<glm::vec2> points;
    stratified_square(1, rng, &points, Interleave{glm::ivec2(1, 2), n, mix64(uint64_t(k) + 99)});
    ASSERT_EQ(points.size(), 1u);
    ++hits[int(points[0].y * 3) * 3 + int(points[0].x * 3)];
  }
  double chi2 = 0.0;
  const double expected = double(draws) / 9.0;
  for (int h : hits) chi2 += (h - expected) * (h - expected) / expected;
  EXPECT_LT(chi2, 26.1);
}

// A 3 x 3 grid of probes 5 cm apart on the floor (normal +Y), 2 x 1 texels each: texel 0
// is the upper hemisphere (content `up_distance` away), texel 1 the lower one (content 1 cm
// away, as the floor under a probe is). Probe p's texel t holds (p + 1)^2 (t + 1).
struct Grid {
  ProbeLayout layout;
  std::vector<ProbeSite> sites;
  Image mosaic;
  TexelRecords records;
  std::vector<uint8_t> computed;

  explicit Grid(float up_distance) {
    layout.grid_height = 3;
    layout.grid_width = 3;
    layout.res_height = 2;
    layout.res_width = 1;
    mosaic = Image(3, 6, 3);
    for (int p = 0; p < 9; ++p) {
      ProbeSite s;
      s.origin = glm::vec3(0.05f * float(p % 3), 0.01f, 0.05f * float(p / 3));
      s.surface = s.origin - glm::vec3(0.0f, 0.01f, 0.0f);
      s.normal = glm::vec3(0.0f, 1.0f, 0.0f);
      s.status = ProbeStatus::kValid;
      sites.push_back(s);
      for (int t = 0; t < 2; ++t) {
        for (int ch = 0; ch < 3; ++ch) mosaic.at(p % 3, (p / 3) * 2 + t, ch) = float((p + 1) * (p + 1) * (t + 1));
        records.distance.push_back(t == 0 ? up_distance : 0.01f);
        records.samples.push_back(4.0f);
        records.variance.push_back(1e4f);  // noisy: the values' differences are noise
      }
    }
    computed.assign(9, 1);
  }
  float centre(int t, const Image& image) const { return image.at(1, 2 + t, 0); }
  Image share(uint64_t* shared = nullptr) const {
    return share_between_neighbours(mosaic, layout, sites, computed, records, ProbeSharing{}, shared);
  }
};

TEST(ProbeSharing, FarContentIsAveragedOverTheWindowNearContentIsNot) {
  const Grid grid(3.0f);  // ceiling 3 m up: parallax of 7 cm there is ~0.02 rad
  uint64_t shared = 0;
  const Image out = grid.share(&shared);
  EXPECT_FLOAT_EQ(grid.centre(0, out), 285.0f / 9.0f);  // mean of 1, 4, ..., 81
  EXPECT_FLOAT_EQ(grid.centre(1, out), 50.0f);          // the floor 1 cm below: its own value
  EXPECT_EQ(shared, 9u);  // the up texel of every probe, none of the down ones
  // Corner probe 0 shares with 1, 3 and 4 only: (1 + 4 + 16 + 25) / 4.
  EXPECT_FLOAT_EQ(out.at(0, 0, 0), 11.5f);
}

TEST(ProbeSharing, ContentAsNearAsTheBaselineIsNotShared) {
  // Half the texel's smaller extent (pi/2) is 0.79 rad; every neighbour's baseline has at
  // least 2.5 cm across the texel's centre direction (60 degrees from the zenith), 1.25 rad
  // seen from 2 cm.
  const Grid grid(0.02f);
  uint64_t shared = 0;
  const Image out = grid.share(&shared);
  EXPECT_FLOAT_EQ(grid.centre(0, out), 25.0f);
  EXPECT_EQ(shared, 0u);
}

TEST(ProbeSharing, WeightsAreSampleCountsAndOtherSurfacesOccludersAndInvalidProbesAreLeftOut) {
  Grid grid(3.0f);
  grid.records.samples[2 * 1 + 0] = 32.0f;          // probe 1 (value 4) was hard: 8x the samples
  grid.sites[3].normal = glm::vec3(1.0f, 0.0f, 0.0f);  // probe 3 (value 16) on a wall
  grid.sites[5].origin.y += 0.1f;                     // probe 5 (value 36) on a step 10 cm up
  grid.records.distance[2 * 7 + 0] = 1.0f;            // probe 7 (value 64) sees an occluder
  grid.sites[8].status = ProbeStatus::kEmitter;        // probe 8 (value 81) is on a light
  grid.computed[6] = 0;                               // probe 6 (value 49) was not rendered
  const Image out = grid.share();
  // Left: probes 0 (1), 1 (4, weight 8), 2 (9) and 4 (25, the centre): (1 + 32 + 9 + 25) / 11.
  EXPECT_FLOAT_EQ(grid.centre(0, out), 67.0f / 11.0f);
  // The emitter probe is not shared into, and is written unchanged.
  EXPECT_FLOAT_EQ(out.at(2, 2 * 2 + 0, 0), 81.0f);
}

// Values further apart than three standard errors of their difference (from the records'
// variances) are left out: a moved edge, not noise.
TEST(ProbeSharing, ValuesFurtherApartThanTheirNoiseAreNotShared) {
  Grid grid(3.0f);
  std::fill(grid.records.variance.begin(), grid.records.variance.end(), 1.0f);
  // The centre's 25 against its neighbours' 1 to 81: at least 9 apart, 3 sqrt(2) allowed.
  EXPECT_FLOAT_EQ(grid.centre(0, grid.share()), 25.0f);
  // 3 sqrt(20) = 13.4: the neighbours 16 and 36 join, 9 (16 apart) and 49 (24) do not.
  std::fill(grid.records.variance.begin(), grid.records.variance.end(), 10.0f);
  EXPECT_FLOAT_EQ(grid.centre(0, grid.share()), (16.0f + 25.0f + 36.0f) / 3.0f);
}

// A shared texel's standard error is that of the sample-weighted mean of independent
// estimates, sqrt(sum n^2 var) / sum n; texels that took in no neighbour keep theirs.
TEST(ProbeSharing, TheSharedTexelsStandardErrorIsTheWeightedMeans) {
  Grid grid(3.0f);
  grid.records.samples[2 * 1 + 0] = 32.0f;  // probe 1 (the centre's neighbour) has 8x the samples
  Image error(3, 6, 1, -1.0f);
  uint64_t shared = 0;
  share_between_neighbours(grid.mosaic, grid.layout, grid.sites, grid.computed, grid.records, ProbeSharing{}, &shared,
                           &error);
  // The centre's up texel: 8 probes of n = 4 and one of 32, each of variance 1e4.
  const double expected = std::sqrt(8.0 * 16.0 * 1e4 + 32.0 * 32.0 * 1e4) / (8.0 * 4.0 + 32.0);
  EXPECT_NEAR(error.at(1, 2, 0), expected, 1e-3 * expected);
  EXPECT_LT(error.at(1, 2, 0), 100.0f);  // below one texel's own sqrt(1e4)
  EXPECT_FLOAT_EQ(error.at(1, 3, 0), -1.0f);  // the down texel was not shared: left as it was
}

TEST(ProbeSharing, RadiusZeroChangesNothing) {
  const Grid grid(3.0f);
  ProbeSharing off;
  off.radius = 0;
  uint64_t shared = 7;
  const Image out = share_between_neighbours(grid.mosaic, grid.layout, grid.sites, grid.computed, grid.records, off, &shared);
  EXPECT_EQ(out.pixels, grid.mosaic.pixels);
}

}  // namespace
}  // namespace phyir::render
