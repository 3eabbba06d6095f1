#pragma once
// A read-only sparse map from (integer cell, normal bucket) to a value, laid out for the
// radiance cache's lookups of the 2 x 2 x 2 cells round a point (docs/probes-estimator.md,
// "The radiance cache": memory layout).
//
// Bricks of 4 x 4 x 4 cells per bucket, one record each in an open-addressing table (key,
// 64-bit presence mask, first value); values stored densely brick by brick, a cell's place
// the count of present cells before it. A lookup's 8 cells lie in one brick in 27 of 64
// positions, so it costs about 2 table probes, not 8, and reads adjacent memory.
#include <algorithm>
#include <array>
#include <cstdint>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "phyir/core/pcg32.h"

namespace phyir::render {

template <typename Value>
class SparseCellGrid {
 public:
  // Cells beyond kCoordLimit on any axis are left out, never wrapped (brick keys exact within).
  static constexpr int kCoordLimit = (1 << 20) - 4;

  struct Entry {
    glm::ivec3 cell;
    int bucket;  // 0..63
    Value value;
  };

  SparseCellGrid() = default;
  // Entries with the same (cell, bucket) must not repeat.
  explicit SparseCellGrid(std::vector<Entry> entries);

  // The value of a cell, nullptr if absent.
  const Value* find(const glm::ivec3& cell, int bucket) const;
  // The values of the 8 cells first + (corner & 1, (corner >> 1) & 1, (corner >> 2) & 1),
  // corner = 0..7; nullptr where absent or where wanted[corner] is false.
  std::array<const Value*, 8> corners(const glm::ivec3& first, int bucket, const std::array<bool, 8>& wanted) const;

  size_t size() const { return values_.size(); }
  size_t brick_count() const { return brick_count_; }

 private:
  static constexpr uint64_t kEmpty = ~uint64_t(0);
  struct Brick {
    uint64_t key = kEmpty;
    uint64_t present = 0;  // bit local_index(cell)
    uint32_t first = 0;    // index into values_ of its first present cell
  };

  static int floor_div4(int c) { return c >= 0 ? c / 4 : -((3 - c) / 4); }
  static glm::ivec3 brick_of(const glm::ivec3& cell) {
    return {floor_div4(cell.x), floor_div4(cell.y), floor_div4(cell.z)};
  }
  static int local_index(const glm::ivec3& cell) { return (cell.x & 3) | (cell.y & 3) << 2 | (cell.z & 3) << 4; }
  // 19 bits per brick coordinate (inside() keeps them within +-2^18), 6 for the bucket:
  // 63 bits, never kEmpty.
  static uint64_t brick_key(const glm::ivec3& brick, int bucket) {
    uint64_t key = 0;
    for (int a = 0; a < 3; ++a) key = (key << 19) | uint64_t(int64_t(brick[a]) + (int64_t(1) << 18));
    return (key << 6) | uint64_t(bucket);
  }
  static bool inside(const glm::ivec3& cell) {
    return glm::all(glm::lessThan(glm::abs(cell), glm::ivec3(kCoordLimit)));
  }
  const Brick* find_brick(uint64_t key) const;
  const Value* value_in(const Brick* brick, int local) const {
    if (!brick || !((brick->present >> local) & 1u)) return nullptr;
    const uint64_t before = brick->present & ((uint64_t(1) << local) - 1);
    return &values_[brick->first + uint32_t(__builtin_popcountll(before))];
  }

  std::vector<Brick> table_;  // power-of-two size, at most half full
  std::vector<Value> values_;
  size_t brick_count_ = 0;
};

template <typename Value>
SparseCellGrid<Value>::SparseCellGrid(std::vector<Entry> entries) {
  // By brick, then place: each brick's values contiguous, in its presence mask's order.
  struct Keyed {
    uint64_t brick;
    int local;
    size_t entry;
  };
  std::vector<Keyed> order;
  order.reserve(entries.size());
  for (size_t n = 0; n < entries.size(); ++n) {
    if (!inside(entries[n].cell)) continue;  // unreachable by lookups
    order.push_back({brick_key(brick_of(entries[n].cell), entries[n].bucket), local_index(entries[n].cell), n});
  }
  std::sort(order.begin(), order.end(), [](const Keyed& a, const Keyed& b) {
    return a.brick != b.brick ? a.brick < b.brick : a.local < b.local;
  });
  std::vector<Brick> bricks;
  values_.reserve(order.size());
  for (const Keyed& k : order) {
    if (bricks.empty() || bricks.back().key != k.brick) bricks.push_back(Brick{k.brick, 0, uint32_t(values_.size())});
    bricks.back().present |= uint64_t(1) << k.local;
    values_.push_back(std::move(entries[k.entry].value));
  }
  brick_count_ = bricks.size();
  size_t capacity = 16;
  while (capacity < 2 * bricks.size()) capacity *= 2;
  table_.assign(capacity, Brick{});
  for (const Brick& b : bricks) {
    size_t slot = mix64(b.key) & (capacity - 1);
    while (table_[slot].key != kEmpty) slot = (slot + 1) & (capacity - 1);
    table_[slot] = b;
  }
}

template <typename Value>
const typename SparseCellGrid<Value>::Brick* SparseCellGrid<Value>::find_brick(uint64_t key) const {
  if (table_.empty()) return nullptr;
  const size_t mask = table_.size() - 1;
  for (size_t slot = mix64(key) & mask;; slot = (slot + 1) & mask) {
    if (table_[slot].key == key) return &table_[slot];
    if (table_[slot].key == kEmpty) return nullptr;
  }
}

template <typename Value>
const Value* SparseCellGrid<Value>::find(const glm::ivec3& cell, int bucket) const {
  if (!inside(cell)) return nullptr;
  return value_in(find_brick(brick_key(brick_of(cell), bucket)), local_index(cell));
}

template <typename Value>
std::array<const Value*, 8> SparseCellGrid<Value>::corners(const glm::ivec3& first, int bucket,
                                                           const std::array<bool, 8>& wanted) const {
  std::array<const Value*, 8> out{};
  if (!inside(first) || !inside(first + 1)) {
    for (int corner = 0; corner < 8; ++corner)
      if (wanted[size_t(corner)])
        out[size_t(corner)] = find(first + glm::ivec3(corner & 1, (corner >> 1) & 1, (corner >> 2) & 1), bucket);
    return out;
  }
  // An axis whose two cells lie in different bricks (first at the brick's last place).
  const glm::ivec3 brick = brick_of(first);
  const glm::ivec3 crosses((first.x & 3) == 3, (first.y & 3) == 3, (first.z & 3) == 3);
  std::array<const Brick*, 8> bricks{};
  std::array<bool, 8> found{};
  for (int corner = 0; corner < 8; ++corner) {
    if (!wanted[size_t(corner)]) continue;
    const glm::ivec3 d(corner & 1, (corner >> 1) & 1, (corner >> 2) & 1);
    const glm::ivec3 step = d * crosses;
    const size_t b = size_t(step.x + 2 * step.y + 4 * step.z);
    if (!found[b]) {
      bricks[b] = find_brick(brick_key(brick + step, bucket));
      found[b] = true;
    }
    out[size_t(corner)] = value_in(bricks[b], local_index(first + d));
  }
  return out;
}

}  // namespace phyir::render
