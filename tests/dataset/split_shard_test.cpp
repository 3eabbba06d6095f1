// Splits by scene (deterministic, fractions respected, a scene's split independent of the
// others) and shards (every view in exactly one shard, contiguous, balanced; i/N parsing).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <map>
#include <vector>

#include "dataset_test_helpers.h"
#include "phyir/core/error.h"
#include "phyir/dataset/layout.h"
#include "phyir/dataset/shard.h"
#include "phyir/dataset/split.h"

namespace phyir::dataset {
namespace {

TEST(Split, DeterministicAndDependsOnlyOnNameAndSeed) {
  const SplitFractions f;
  for (int i = 0; i < 200; ++i) {
    const std::string name = "room_" + std::to_string(i);
    EXPECT_EQ(split_for_scene(name, 5, f), split_for_scene(name, 5, f));
  }
  // Another seed reshuffles.
  int moved = 0;
  for (int i = 0; i < 200; ++i) {
    const std::string name = "room_" + std::to_string(i);
    moved += split_for_scene(name, 5, f) != split_for_scene(name, 6, f);
  }
  EXPECT_GT(moved, 20);
}

TEST(Split, FractionsAreRespectedOverManyScenes) {
  const SplitFractions f{0.7, 0.2, 0.1};
  std::map<Split, int> count;
  const int n = 4000;
  for (int i = 0; i < n; ++i) count[split_for_scene("scene_" + std::to_string(i), 1, f)]++;
  // Binomial standard deviation at n = 4000 is below 0.008; allow 4 sigma.
  EXPECT_NEAR(count[Split::Train] / double(n), 0.7, 0.03);
  EXPECT_NEAR(count[Split::Val] / double(n), 0.2, 0.03);
  EXPECT_NEAR(count[Split::Test] / double(n), 0.1, 0.03);
  const SplitFractions all_train{1.0, 0.0, 0.0};
  for (int i = 0; i < 100; ++i) EXPECT_EQ(split_for_scene("s" + std::to_string(i), 1, all_train), Split::Train);
}

TEST(Split, ViewSeedsIndependentOfEverythingElse) {
  EXPECT_EQ(view_seed(1, "room_0", 3), view_seed(1, "room_0", 3));
  EXPECT_NE(view_seed(1, "room_0", 3), view_seed(1, "room_0", 4));
  EXPECT_NE(view_seed(1, "room_0", 3), view_seed(2, "room_0", 3));
  EXPECT_LT(view_seed(1, "room_0", 3), uint64_t(1) << 53);
  EXPECT_EQ(view_id("room_0", 7, 8), "room_0/v007");
  EXPECT_EQ(view_id("room_0", 7, 2000), "room_0/v0007");
}

TEST(Shard, PartitionCoversEveryViewExactlyOnce) {
  for (size_t total : {0u, 1u, 2u, 7u, 64u, 1001u}) {
    for (int n = 1; n <= 9; ++n) {
      std::vector<int> owner(total, -1);
      size_t expected_begin = 0;
      for (int i = 0; i < n; ++i) {
        const auto [begin, end] = shard_range(total, {i, n});
        EXPECT_EQ(begin, expected_begin) << "contiguous";
        EXPECT_LE(end - begin, total / n + 1) << "balanced";
        EXPECT_GE(end - begin, total / n);
        for (size_t g = begin; g < end; ++g) {
          EXPECT_EQ(owner[g], -1) << "view " << g << " in two shards";
          owner[g] = i;
        }
        expected_begin = end;
      }
      EXPECT_EQ(expected_begin, total);
      for (size_t g = 0; g < total; ++g) EXPECT_GE(owner[g], 0) << "view " << g << " in no shard";
    }
  }
}

TEST(Shard, ParsesIOverN) {
  EXPECT_EQ(parse_shard("0/1").count, 1);
  EXPECT_EQ(parse_shard("3/4").index, 3);
  EXPECT_EQ(shard_name(parse_shard("2/5")), "2/5");
  for (const char* bad : {"4/4", "-1/4", "1/0", "1", "a/b", "1/2x", ""}) {
    try {
      parse_shard(bad);
      ADD_FAILURE() << "accepted '" << bad << "'";
    } catch (const Error& e) {
      EXPECT_THAT(e.what(), ::testing::HasSubstr("shard: '"));
    }
  }
}

}  // namespace
}  // namespace phyir::dataset
