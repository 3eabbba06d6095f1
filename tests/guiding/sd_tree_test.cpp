// The SD-tree (render/guiding): leaves split where the records are, the guide at a point
// learns that point's light, records merged in chunk order give the same tree whatever the
// thread count and schedule, and bad records are dropped and counted.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <thread>
#include <vector>

#include "phyir/core/error.h"
#include "phyir/core/pcg32.h"
#include "phyir/core/safe_math.h"
#include "phyir/core/setting_error.h"
#include "phyir/render/guiding/cylindrical_map.h"
#include "phyir/render/guiding/ordered_record_merge.h"
#include "phyir/render/guiding/sd_tree.h"

namespace phyir::render::guiding {
namespace {

const glm::vec3 kMin(0.0f), kMax(4.0f, 3.0f, 2.5f);

// A record at a random point of the box (x < `x_max`), direction uniform, radiance 50 along
// +z in the left half of the room (x < 2) and along -z in the right half, 1 elsewhere.
RadianceRecord random_record(Pcg32* rng, float x_max = 4.0f) {
  RadianceRecord r;
  r.position = glm::vec3(x_max * rng->next_float(), 3.0f * rng->next_float(), 2.5f * rng->next_float());
  r.direction = square_to_direction(rng->next_2d());
  const glm::vec3 light = r.position.x < 2.0f ? glm::vec3(0, 0, 1) : glm::vec3(0, 0, -1);
  r.radiance = glm::dot(r.direction, light) > 0.9f ? 50.0f : 1.0f;
  r.pdf = 1.0f / kSphereArea;
  return r;
}

// Chunks of records, as tiles of a pass would make them.
std::vector<RecordBuffer> chunks_of_records(int chunks, int per_chunk, uint64_t seed, float x_max = 4.0f) {
  std::vector<RecordBuffer> out(chunks);
  for (int c = 0; c < chunks; ++c) {
    Pcg32 rng(seed, uint64_t(c));
    for (int i = 0; i < per_chunk; ++i) out[c].push_back(random_record(&rng, x_max));
  }
  return out;
}

SDTreeSettings small_threshold() {
  SDTreeSettings s;
  s.spatial_threshold = 500.0;
  return s;
}

TEST(SDTree, UntrainedIsUniformEverywhere) {
  const SDTree tree(kMin, kMax);
  EXPECT_FALSE(tree.trained());
  EXPECT_FLOAT_EQ(tree.guide_at(glm::vec3(1, 1, 1)).pdf(glm::vec3(0, 1, 0)), 1.0f / kSphereArea);
  // Points outside the bounds, and NaN points, still find a leaf.
  EXPECT_FLOAT_EQ(tree.guide_at(glm::vec3(-100, 5, 9)).pdf(glm::vec3(0, 1, 0)), 1.0f / kSphereArea);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  EXPECT_FLOAT_EQ(tree.guide_at(glm::vec3(nan)).pdf(glm::vec3(0, 1, 0)), 1.0f / kSphereArea);
  // A pass without records leaves it untrained.
  SDTree empty(kMin, kMax);
  empty.finish_pass(0);
  EXPECT_FALSE(empty.trained());
  EXPECT_EQ(empty.stats().spatial_leaves, 1u);
}

TEST(SDTree, DegenerateBoundsStillWork) {
  SDTree tree(glm::vec3(1.0f), glm::vec3(1.0f));  // a single point
  Pcg32 rng(1, 1);
  for (int i = 0; i < 100; ++i) tree.record(random_record(&rng));
  tree.finish_pass(0);
  EXPECT_TRUE(tree.trained());
}

TEST(SDTree, BadRecordsAreDroppedAndCounted) {
  SDTree tree(kMin, kMax);
  const float inf = std::numeric_limits<float>::infinity(), nan = std::numeric_limits<float>::quiet_NaN();
  RadianceRecord good;
  good.position = glm::vec3(1.0f);
  good.radiance = 1.0f;
  good.pdf = 0.1f;
  std::vector<RadianceRecord> bad(6, good);
  bad[0].radiance = nan;
  bad[1].radiance = inf;
  bad[2].radiance = -1.0f;
  bad[3].pdf = 0.0f;
  bad[4].pdf = nan;
  bad[5].position.y = inf;
  for (const RadianceRecord& r : bad) EXPECT_FALSE(tree.record(r));
  EXPECT_TRUE(tree.record(good));
  EXPECT_EQ(tree.stats().rejected_records, 6u);
  EXPECT_EQ(tree.stats().records, 1u);
  tree.finish_pass(0);
  const float pdf = tree.guide_at(glm::vec3(1.0f)).pdf(glm::vec3(0, 0, 1));
  EXPECT_TRUE(std::isfinite(pdf));
}

TEST(SDTree, LeavesSplitWhereTheRecordsAre) {
  SDTree tree(kMin, kMax, small_threshold());
  // Every record in the left quarter of the box (x < 1). A leaf splits by its own count,
  // its children assumed to share it evenly (the paper's rule): after pass 0 the whole box is
  // split alike; after pass 1 only the leaves that saw records split again.
  for (int pass = 0; pass < 2; ++pass) {
    for (const RecordBuffer& chunk : chunks_of_records(8, 1000, 3 + pass, 1.0f)) tree.record(chunk);
    tree.finish_pass(pass);
    EXPECT_GT(tree.stats().spatial_leaves, 8u);
  }
  const int busy = tree.spatial_depth_at(glm::vec3(0.5f, 1.5f, 1.2f));
  const int empty = tree.spatial_depth_at(glm::vec3(3.5f, 1.5f, 1.2f));
  EXPECT_GT(busy, empty);
  // The threshold grows with the pass (c sqrt(2^k)): the same records at pass 10 split less.
  SDTree early(kMin, kMax, small_threshold()), late(kMin, kMax, small_threshold());
  for (const RecordBuffer& chunk : chunks_of_records(8, 1000, 3, 1.0f)) early.record(chunk), late.record(chunk);
  early.finish_pass(0);
  late.finish_pass(10);
  EXPECT_LT(late.stats().spatial_leaves, early.stats().spatial_leaves);
  // Below the threshold nothing splits.
  SDTree quiet(kMin, kMax, small_threshold());
  quiet.record(chunks_of_records(1, 400, 5)[0]);
  quiet.finish_pass(0);
  EXPECT_EQ(quiet.stats().spatial_leaves, 1u);
}

// The share of `guide`'s samples within 25 degrees of `axis`.
double mass_near(const DirectionalQuadtree& guide, const glm::vec3& axis) {
  Pcg32 rng(21, 4);
  int near = 0;
  for (int i = 0; i < 20000; ++i) near += glm::dot(guide.sample(rng.next_2d()), axis) > 0.9f;
  return near / 20000.0;
}

TEST(SDTree, GuideLearnsTheLightOfEachRegion) {
  SDTree tree(kMin, kMax, small_threshold());
  for (int pass = 0; pass < 3; ++pass) {
    for (const RecordBuffer& chunk : chunks_of_records(16, 2000, 10 + pass)) tree.record(chunk);
    tree.finish_pass(pass);
  }
  ASSERT_TRUE(tree.trained());
  // 50 x 5% against 95% x 1: a good guide puts ~70% of its samples in the bright cone.
  const DirectionalQuadtree& left = tree.guide_at(glm::vec3(0.5f, 1.5f, 1.0f));
  const DirectionalQuadtree& right = tree.guide_at(glm::vec3(3.5f, 1.5f, 1.0f));
  EXPECT_GT(mass_near(left, glm::vec3(0, 0, 1)), 0.4);
  EXPECT_LT(mass_near(left, glm::vec3(0, 0, -1)), 0.1);
  EXPECT_GT(mass_near(right, glm::vec3(0, 0, -1)), 0.4);
  EXPECT_LT(mass_near(right, glm::vec3(0, 0, 1)), 0.1);
}

// Every pdf of the tree at a few points and directions: equal vectors, equal trees.
std::vector<float> fingerprint(const SDTree& tree) {
  std::vector<float> out;
  Pcg32 rng(99, 0);
  for (int i = 0; i < 2000; ++i) {
    const glm::vec3 p(4.0f * rng.next_float(), 3.0f * rng.next_float(), 2.5f * rng.next_float());
    out.push_back(tree.guide_at(p).pdf(square_to_direction(rng.next_2d())));
  }
  const SDTreeStats s = tree.stats();
  out.push_back(float(s.spatial_leaves));
  out.push_back(float(s.quadtree_nodes));
  return out;
}

// Trains two passes with `threads` workers taking chunks in an interleaved order.
SDTree train_with_threads(int threads) {
  SDTree tree(kMin, kMax, small_threshold());
  for (int pass = 0; pass < 2; ++pass) {
    const std::vector<RecordBuffer> chunks = chunks_of_records(24, 700, 40 + pass);
    OrderedRecordMerge merge(&tree, chunks.size());
    std::vector<std::thread> workers;
    for (int t = 0; t < threads; ++t) {
      workers.emplace_back([&, t] {
        // Worker t submits its chunks last-first: the merge must reorder them.
        for (int c = int(chunks.size()) - 1 - t; c >= 0; c -= threads) merge.submit(size_t(c), RecordBuffer(chunks[c]));
      });
    }
    for (std::thread& w : workers) w.join();
    EXPECT_TRUE(merge.complete());
    tree.finish_pass(pass);
  }
  return tree;
}

TEST(SDTree, SameRecordsSameTreeWhateverTheThreadCount) {
  const std::vector<float> one = fingerprint(train_with_threads(1));
  const std::vector<float> two = fingerprint(train_with_threads(2));
  const std::vector<float> three = fingerprint(train_with_threads(3));
  EXPECT_EQ(one, two);
  EXPECT_EQ(one, three);
}

TEST(SDTree, MergeRejectsAChunkTwice) {
  SDTree tree(kMin, kMax);
  OrderedRecordMerge merge(&tree, 2);
  merge.submit(1, {});
  EXPECT_THROW(merge.submit(1, {}), Error);
  EXPECT_THROW(merge.submit(5, {}), Error);
  EXPECT_FALSE(merge.complete());
  merge.submit(0, {});
  EXPECT_TRUE(merge.complete());
}

TEST(SDTree, SettingsAreChecked) {
  SDTreeSettings s;
  s.spatial_threshold = 0.0;
  EXPECT_THROW(SDTree(kMin, kMax, s), SettingError);
  s = SDTreeSettings{};
  s.energy_threshold = 1.5f;
  EXPECT_THROW(SDTree(kMin, kMax, s), SettingError);
}

}  // namespace
}  // namespace phyir::render::guiding
