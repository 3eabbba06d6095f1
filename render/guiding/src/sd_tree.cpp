#include "phyir/render/guiding/sd_tree.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "phyir/core/setting_error.h"
#include "phyir/render/guiding/cylindrical_map.h"

namespace phyir::render::guiding {

void SDTreeSettings::validate() const {
  if (!(spatial_threshold >= 1.0))
    fail_setting("guiding.spatial_threshold", "{} must be at least 1 (records per leaf)", spatial_threshold);
  if (!(energy_threshold > 0.0f && energy_threshold < 1.0f))
    fail_setting("guiding.energy_threshold", "{} must be in (0, 1)", energy_threshold);
  if (max_quadtree_depth < 1 || max_quadtree_depth > 30)
    fail_setting("guiding.max_quadtree_depth", "{} must be between 1 and 30", max_quadtree_depth);
  if (max_spatial_depth < 0 || max_spatial_depth > 60)
    fail_setting("guiding.max_spatial_depth", "{} must be between 0 and 60", max_spatial_depth);
}

SDTree::SDTree(const glm::vec3& min, const glm::vec3& max, const SDTreeSettings& settings)
    : settings_(settings), spatial_(min, max), leaves_(1) {
  settings_.validate();
}

const DirectionalQuadtree& SDTree::guide_at(const glm::vec3& p) const {
  return leaves_[spatial_.slot_at(p)].sampling;
}

bool SDTree::record(const RadianceRecord& r) {
  const bool valid = std::isfinite(r.radiance) && r.radiance >= 0.0f && std::isfinite(r.pdf) && r.pdf > 0.0f &&
                     std::isfinite(r.position.x + r.position.y + r.position.z) &&
                     std::isfinite(r.direction.x + r.direction.y + r.direction.z);
  if (!valid) {
    ++rejected_;
    return false;
  }
  Leaf& leaf = leaves_[spatial_.slot_at(r.position)];
  leaf.building.record(direction_to_square(r.direction), double(r.radiance) / double(r.pdf));
  ++leaf.records;
  ++records_;
  return true;
}

void SDTree::record(const RecordBuffer& records) {
  for (const RadianceRecord& r : records) record(r);
}

// A leaf with more than `threshold` records splits, and its children (each assumed to have
// half) split again while they would still exceed it; both children keep the leaf's trees.
void SDTree::split_busy_leaves(double threshold) {
  const uint32_t slots = uint32_t(leaves_.size());
  for (uint32_t slot = 0; slot < slots; ++slot) {
    // Slots this split creates are processed by the inner loop, at half the count each time.
    std::vector<std::pair<uint32_t, double>> todo{{slot, double(leaves_[slot].records)}};
    while (!todo.empty()) {
      const auto [s, count] = todo.back();
      todo.pop_back();
      if (!(count > threshold)) continue;
      const uint32_t upper = spatial_.split(s, settings_.max_spatial_depth);
      if (upper == UINT32_MAX) continue;
      Leaf copy = leaves_[s];
      leaves_.push_back(std::move(copy));
      todo.push_back({s, count / 2.0});
      todo.push_back({upper, count / 2.0});
    }
  }
}

void SDTree::finish_pass(int pass) {
  split_busy_leaves(settings_.spatial_threshold * std::sqrt(std::ldexp(1.0, pass)));
  bool learned = false;
  for (Leaf& leaf : leaves_) {
    // A leaf that saw nothing this pass keeps what it knew.
    if (leaf.building.total() > 0.0) {
      leaf.sampling = leaf.building;
      leaf.sampling.finalize();
      learned = true;
    }
    leaf.building = leaf.sampling.refined(settings_.energy_threshold, settings_.max_quadtree_depth);
    leaf.records = 0;
  }
  trained_ = trained_ || learned;
  ++passes_;
}

SDTreeStats SDTree::stats() const {
  SDTreeStats s;
  s.passes = passes_;
  s.spatial_leaves = uint32_t(leaves_.size());
  for (const Leaf& leaf : leaves_) {
    s.quadtree_nodes += leaf.sampling.node_count();
    s.max_quadtree_depth = std::max(s.max_quadtree_depth, leaf.sampling.depth());
  }
  s.records = records_;
  s.rejected_records = rejected_;
  return s;
}

}  // namespace phyir::render::guiding
