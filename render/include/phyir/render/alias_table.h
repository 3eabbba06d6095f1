#pragma once
// Walker's alias method (Vose's construction): an index drawn with probability weight / sum
// from one uniform number in O(1), reading one table entry. For large tables sampled at
// random, such as an environment map's texels, where Distribution1D's binary search misses
// the cache at nearly every step. Same contract as Distribution1D: zero-weight (and
// non-finite) entries are never drawn, and `remapped` is uniform in [0,1) given the index.
// Two uniforms: one picks the bin, the other decides between the bin and its alias (from one
// float alone, a table of 2^19 texels would leave that decision 5 bits).
#include <vector>

namespace phyir::render {

class AliasTable {
 public:
  AliasTable() = default;
  explicit AliasTable(const std::vector<float>& weights);
  // -1 when empty. `remapped`: u_keep rescaled to [0,1) within the decision it made.
  int sample(float u_bin, float u_keep, float* pmf = nullptr, float* remapped = nullptr) const;
  float pmf(int index) const;
  // Starts loading the bin `u_bin` will read (sample()'s first uniform) and returns its
  // index: a large table misses the cache at every draw, so a caller that knows its uniform
  // early hides that wait behind other work (a ray being traced). -1 when empty.
  int prefetch(float u_bin) const;
  int size() const { return static_cast<int>(bins_.size()); }
  bool empty() const { return !(total_ > 0.0); }
  double total() const { return total_; }

 private:
  // Bin i keeps i with probability `keep`, else gives `alias`; both pmfs sit in the bin, so
  // a draw reads one entry.
  struct Bin {
    float keep = 1.0f;
    int alias = 0;
    float pmf = 0.0f;
    float alias_pmf = 0.0f;
  };
  int bin_of(float u_bin) const;
  std::vector<Bin> bins_;
  double total_ = 0.0;
};

}  // namespace phyir::render
