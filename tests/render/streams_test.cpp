// The random-stream registry (render/include/phyir/render/streams.h): every purpose's
// streams are apart from every other's, for every index a renderer uses, and a stream is a
// pure function of its key, purpose and index (what makes images bit-identical whatever the
// thread count).
#include <gtest/gtest.h>

#include <cstdint>
#include <unordered_set>
#include <vector>

#include "phyir/render/streams.h"

namespace phyir::render {
namespace {

const std::vector<Purpose> kPurposes = {
    Purpose::kPathBrdf,           Purpose::kPathLight,          Purpose::kPathEnvironment,
    Purpose::kPathRoulette,       Purpose::kPathGlass,          Purpose::kCacheFallbackDirection,
    Purpose::kCacheFillDirections, Purpose::kCacheFillLight,    Purpose::kCacheFillLightPoints,
    Purpose::kCachePoint,         Purpose::kTexelLight,         Purpose::kTexelBrdf,
    Purpose::kTexelLookup,        Purpose::kTexelGlass,         Purpose::kTexelSpecularRoulette,
    Purpose::kTexelLightRepeat,   Purpose::kProbeDiscovery,     Purpose::kProbeStrata,
    Purpose::kProbeInterleave,    Purpose::kProbeLightPart,     Purpose::kProbeCacheTieBreak,
    Purpose::kPixelScramble,      Purpose::kPixelLightSelect,   Purpose::kPixelLightPoint,
    Purpose::kPixelLobe,          Purpose::kPixelBrdf,          Purpose::kProbeSeed,
    Purpose::kCacheSeed};

TEST(Streams, EveryPurposeAndIndexHasItsOwnKey) {
  // 64 samples of 8 items x every purpose x indices 0..63 (bounces, depths, batch starts):
  // no two keys are equal, and none equals a sample key itself.
  std::unordered_set<uint64_t> keys;
  size_t count = 0;
  for (uint64_t item = 0; item < 8; ++item)
    for (uint64_t sample = 0; sample < 64; ++sample) {
      const uint64_t key = sample_key(7, item, sample);
      keys.insert(key);
      ++count;
      for (Purpose p : kPurposes)
        for (uint64_t index = 0; index < 64; ++index) {
          keys.insert(stream_key(key, p, index));
          ++count;
        }
    }
  EXPECT_EQ(keys.size(), count);
}

TEST(Streams, AStreamIsAFunctionOfItsKeyPurposeAndIndex) {
  Rng a = stream(sample_key(1, 2, 3), Purpose::kPathBrdf, 4);
  Rng b = stream(sample_key(1, 2, 3), Purpose::kPathBrdf, 4);
  Rng c = stream(sample_key(1, 2, 3), Purpose::kPathBrdf, 5);
  int same_as_c = 0;
  for (int i = 0; i < 100; ++i) {
    const uint32_t x = a.next_u32();
    EXPECT_EQ(x, b.next_u32());
    same_as_c += x == c.next_u32();
  }
  EXPECT_LT(same_as_c, 3);
  EXPECT_EQ(item_stream_key(1, 2, Purpose::kProbeStrata, 3), item_stream_key(1, 2, Purpose::kProbeStrata, 3));
  EXPECT_NE(item_stream_key(1, 2, Purpose::kProbeStrata, 3), item_stream_key(1, 3, Purpose::kProbeStrata, 3));
}

TEST(Streams, NeighbouringKeysGiveUncorrelatedFirstNumbers) {
  // The first float of the streams of 20000 consecutive samples: mean 1/2, and lag-1
  // correlation near 0 (a weak derivation, e.g. key + purpose, correlates neighbours).
  constexpr int n = 20000;
  std::vector<double> u(n);
  for (int i = 0; i < n; ++i) u[size_t(i)] = stream(sample_key(3, 0, uint64_t(i)), Purpose::kPathLight, 1).next_float();
  double mean = 0.0, lag = 0.0, var = 0.0;
  for (double v : u) mean += v / n;
  for (int i = 0; i < n; ++i) {
    var += (u[size_t(i)] - mean) * (u[size_t(i)] - mean);
    if (i > 0) lag += (u[size_t(i)] - mean) * (u[size_t(i - 1)] - mean);
  }
  EXPECT_NEAR(mean, 0.5, 4.0 * std::sqrt(1.0 / 12.0 / n));
  EXPECT_NEAR(lag / var, 0.0, 4.0 / std::sqrt(double(n)));
}

}  // namespace
}  // namespace phyir::render
