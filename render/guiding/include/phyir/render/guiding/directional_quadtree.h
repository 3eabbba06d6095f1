#pragma once
// The directional half of the SD-tree (Müller et al. 2017, section 3.2): a quadtree over the
// cylindrical square (cylindrical_map.h) whose nodes hold the energy (summed radiance over
// density, an estimate of the integral of incident radiance over the cell) of their four
// children. Sampling descends by energy and ends uniform in a leaf; the density is the
// product of 4 E_child / E_node along the way, so sample() and pdf() agree exactly.
//
// Recording changes the energies only; finalize() turns them into the distribution that
// pdf() and sample() read (each node's four shares, so a lookup multiplies, never divides). A
// tree samples the distribution of its last finalize(), uniform before one or without energy.
// Between passes the structure is rebuilt from the energies (refined()): a cell holding more
// than a fraction rho of the total is split.
#include <array>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

namespace phyir::render::guiding {

// The paper's subdivision threshold: a cell is split while it holds more than 1% of the
// energy, so a tree has at most a few hundred leaves whatever its records.
constexpr float kDefaultEnergyThreshold = 0.01f;
// The paper's depth limit: cells of 2^-20 of the square's side, far below any lobe.
constexpr int kDefaultMaxQuadtreeDepth = 20;

class DirectionalQuadtree {
 public:
  DirectionalQuadtree();  // a root with four empty leaves: uniform

  // Adds `value` (>= 0, finite: the caller checks) to every cell containing square point p.
  void record(const glm::vec2& p, double value);
  double total() const;
  // Makes the recorded energies the distribution pdf() and sample() follow.
  void finalize();

  // Density over the unit square (1 everywhere for an empty tree).
  float pdf_square(const glm::vec2& p) const;
  // A square point with that density, from two uniform numbers.
  glm::vec2 sample_square(const glm::vec2& u) const;
  // The same over the sphere of unit directions (solid-angle density).
  float pdf(const glm::vec3& direction) const;
  glm::vec3 sample(const glm::vec2& u) const;

  // A tree with this one's structure refined by its energies (a cell is split when it holds
  // more than `threshold` of the total, down to `max_depth`) and no energy.
  DirectionalQuadtree refined(float threshold = kDefaultEnergyThreshold,
                              int max_depth = kDefaultMaxQuadtreeDepth) const;

  size_t node_count() const { return nodes_.size(); }
  int depth() const;

 private:
  // child[c] == 0: child c is a leaf (node 0, the root, is nobody's child). Child c covers
  // the quarter x >= 1/2 when (c & 1), y >= 1/2 when (c & 2).
  struct Node {
    std::array<double, 4> energy{};
    std::array<float, 4> share{0.25f, 0.25f, 0.25f, 0.25f};  // energy[c] / sum, as of finalize()
    std::array<uint32_t, 4> child{};
    double sum() const { return energy[0] + energy[1] + energy[2] + energy[3]; }
  };
  void refine_into(DirectionalQuadtree* out, uint32_t old_node, uint32_t new_node,
                   const std::array<double, 4>& child_energy, double total, float threshold, int depth,
                   int max_depth) const;
  int depth_below(uint32_t node) const;

  std::vector<Node> nodes_;
};

}  // namespace phyir::render::guiding
