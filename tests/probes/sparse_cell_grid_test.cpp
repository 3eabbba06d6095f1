// The radiance cache's lookup structure (render/include/phyir/render/sparse_cell_grid.h):
// every find and every corner query against a plain std::map, across brick boundaries and
// negative coordinates, and cells beyond its range.
#include <gtest/gtest.h>

#include <map>
#include <random>
#include <tuple>

#include "sparse_cell_grid.h"

namespace phyir::render {
namespace {

using Grid = SparseCellGrid<int>;
using Key = std::tuple<int, int, int, int>;  // x, y, z, bucket

Key key_of(const glm::ivec3& c, int bucket) { return {c.x, c.y, c.z, bucket}; }

const int* brute(const std::map<Key, int>& truth, const glm::ivec3& c, int bucket) {
  const auto it = truth.find(key_of(c, bucket));
  return it == truth.end() ? nullptr : &it->second;
}

// Random cells in [-9, 9]^3 (straddling the origin, where floor division matters) in three
// buckets, each present with probability 1/3.
struct Fixture {
  std::map<Key, int> truth;
  Grid grid;
  Fixture() {
    std::mt19937 rng(7);
    std::vector<Grid::Entry> entries;
    int value = 0;
    for (int x = -9; x <= 9; ++x)
      for (int y = -9; y <= 9; ++y)
        for (int z = -9; z <= 9; ++z)
          for (int bucket : {0, 17, 53})
            if (rng() % 3 == 0) {
              entries.push_back({glm::ivec3(x, y, z), bucket, value});
              truth[key_of(glm::ivec3(x, y, z), bucket)] = value++;
            }
    std::shuffle(entries.begin(), entries.end(), rng);  // the build must not rely on order
    grid = Grid(std::move(entries));
  }
};

TEST(SparseCellGrid, FindsExactlyTheCellsItHolds) {
  const Fixture f;
  EXPECT_EQ(f.grid.size(), f.truth.size());
  for (int x = -11; x <= 11; ++x)
    for (int y = -11; y <= 11; ++y)
      for (int z = -11; z <= 11; ++z)
        for (int bucket : {0, 1, 17, 53}) {
          const glm::ivec3 c(x, y, z);
          const int* got = f.grid.find(c, bucket);
          const int* want = brute(f.truth, c, bucket);
          ASSERT_EQ(got == nullptr, want == nullptr) << x << " " << y << " " << z << " bucket " << bucket;
          if (want) {
            EXPECT_EQ(*got, *want);
          }
        }
}

TEST(SparseCellGrid, CornersMatchEightFinds) {
  const Fixture f;
  std::mt19937 rng(11);
  for (int x = -11; x <= 10; ++x)
    for (int y = -11; y <= 10; ++y)
      for (int z = -11; z <= 10; ++z) {
        const glm::ivec3 first(x, y, z);
        std::array<bool, 8> wanted;
        for (bool& w : wanted) w = rng() % 4 != 0;
        const int bucket = (x + y + z) % 2 == 0 ? 17 : 53;
        const auto corners = f.grid.corners(first, bucket, wanted);
        for (int corner = 0; corner < 8; ++corner) {
          const glm::ivec3 c = first + glm::ivec3(corner & 1, (corner >> 1) & 1, (corner >> 2) & 1);
          const int* want = wanted[size_t(corner)] ? brute(f.truth, c, bucket) : nullptr;
          ASSERT_EQ(corners[size_t(corner)] == nullptr, want == nullptr) << x << " " << y << " " << z << " corner " << corner;
          if (want) {
            EXPECT_EQ(*corners[size_t(corner)], *want);
          }
        }
      }
}

TEST(SparseCellGrid, BricksAreFourCellsWideWithFloorDivision) {
  // Cells -4..-1 share a brick, 0..3 the next: 8 cells in 2 bricks, one bucket.
  std::vector<Grid::Entry> entries;
  for (int x = -4; x <= 3; ++x) entries.push_back({glm::ivec3(x, 0, 0), 5, x});
  const Grid grid(std::move(entries));
  EXPECT_EQ(grid.brick_count(), 2u);
  for (int x = -4; x <= 3; ++x) ASSERT_NE(grid.find(glm::ivec3(x, 0, 0), 5), nullptr);
  EXPECT_EQ(*grid.find(glm::ivec3(-1, 0, 0), 5), -1);
  EXPECT_EQ(grid.find(glm::ivec3(-5, 0, 0), 5), nullptr);
  EXPECT_EQ(grid.find(glm::ivec3(0, 0, 0), 4), nullptr);  // another bucket
}

TEST(SparseCellGrid, CellsBeyondItsRangeAreLeftOutNotWrapped) {
  const int limit = Grid::kCoordLimit;
  std::vector<Grid::Entry> entries = {{glm::ivec3(limit, 0, 0), 0, 1},
                                      {glm::ivec3(limit - 1, 0, 0), 0, 2},
                                      {glm::ivec3(0, -limit + 1, 0), 0, 3},
                                      {glm::ivec3(0, 0, -limit), 0, 4}};
  const Grid grid(std::move(entries));
  EXPECT_EQ(grid.size(), 2u);
  EXPECT_EQ(grid.find(glm::ivec3(limit, 0, 0), 0), nullptr);
  EXPECT_EQ(*grid.find(glm::ivec3(limit - 1, 0, 0), 0), 2);
  EXPECT_EQ(*grid.find(glm::ivec3(0, -limit + 1, 0), 0), 3);
  EXPECT_EQ(grid.find(glm::ivec3(0, 0, -limit), 0), nullptr);
  EXPECT_EQ(grid.find(glm::ivec3(2000000000, -2000000000, 0), 0), nullptr);
  // Corners straddling the limit: the cell inside is found, the one outside is not.
  std::array<bool, 8> all;
  all.fill(true);
  const auto corners = grid.corners(glm::ivec3(limit - 1, 0, 0), 0, all);
  ASSERT_NE(corners[0], nullptr);
  EXPECT_EQ(*corners[0], 2);
  for (int corner = 1; corner < 8; ++corner) EXPECT_EQ(corners[size_t(corner)], nullptr);
}

TEST(SparseCellGrid, EmptyGridFindsNothing) {
  const Grid grid;
  EXPECT_EQ(grid.find(glm::ivec3(0), 0), nullptr);
  std::array<bool, 8> all;
  all.fill(true);
  for (const int* v : grid.corners(glm::ivec3(-1), 3, all)) EXPECT_EQ(v, nullptr);
}

}  // namespace
}  // namespace phyir::render
