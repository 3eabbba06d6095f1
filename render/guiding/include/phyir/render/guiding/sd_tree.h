#pragma once
// The SD-tree of Müller et al. 2017: a spatial binary tree (spatial_tree.h) whose every leaf
// holds two directional quadtrees (directional_quadtree.h): the *sampling* tree, learned in
// the passes so far, which guides paths; and the *building* tree, which this pass's records
// fill. finish_pass() ends a pass: leaves that received many records split, building trees
// become sampling trees, and new building trees get the structure their energies call for.
//
// Recording is single-threaded: renderers buffer records per chunk of work and hand the
// buffers over in a fixed order (ordered_record_merge.h), so the energies are the same sums
// in the same order whatever the thread count. Sampling (guide_at) is const and thread-safe.
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "phyir/render/guiding/directional_quadtree.h"
#include "phyir/render/guiding/radiance_record.h"
#include "phyir/render/guiding/spatial_tree.h"

namespace phyir::render::guiding {

struct SDTreeSettings {
  // c of the paper's spatial split: a leaf splits after pass k when it received more than
  // c sqrt(2^k) records. The paper's 12000 is for megapixel images; ours have 4-30 times fewer
  // paths, and 4000 keeps a few thousand records per leaf (docs/guiding.md).
  double spatial_threshold = 4000.0;
  float energy_threshold = kDefaultEnergyThreshold;  // rho
  int max_quadtree_depth = kDefaultMaxQuadtreeDepth;
  // Cells of 2^-8 of the cube's side (~4 cm in a 10 m room) along each axis: finer cells
  // would see too few records to learn from.
  int max_spatial_depth = 24;

  void validate() const;  // SettingError naming "guiding.spatial_threshold", ...
};

struct SDTreeStats {
  uint32_t passes = 0;             // finish_pass() calls
  uint32_t spatial_leaves = 0;
  uint64_t quadtree_nodes = 0;     // of the sampling trees, summed over leaves
  int max_quadtree_depth = 0;
  uint64_t records = 0;            // kept, over every pass
  uint64_t rejected_records = 0;   // not finite, negative, or without density
};

class SDTree {
 public:
  // A tree over the box [min, max] (the scene's bounds).
  SDTree(const glm::vec3& min, const glm::vec3& max, const SDTreeSettings& settings = {});

  // The learned directional distribution at p (uniform before any pass has finished).
  const DirectionalQuadtree& guide_at(const glm::vec3& p) const;
  // Whether some pass has finished with records: before, the guide is uniform everywhere.
  bool trained() const { return trained_; }

  // Adds one record to the building tree at its position; false (and counted) when rejected.
  bool record(const RadianceRecord& r);
  void record(const RecordBuffer& records);

  // Ends training pass `pass` (0, 1, ...).
  void finish_pass(int pass);

  SDTreeStats stats() const;
  // The depth of the spatial leaf holding p (0: the whole box).
  int spatial_depth_at(const glm::vec3& p) const { return spatial_.depth_of(spatial_.slot_at(p)); }

 private:
  struct Leaf {
    DirectionalQuadtree sampling;
    DirectionalQuadtree building;
    uint64_t records = 0;  // this pass's
  };
  void split_busy_leaves(double threshold);

  SDTreeSettings settings_;
  SpatialTree spatial_;
  std::vector<Leaf> leaves_;  // per slot of spatial_
  bool trained_ = false;
  uint32_t passes_ = 0;
  uint64_t records_ = 0, rejected_ = 0;
};

}  // namespace phyir::render::guiding
