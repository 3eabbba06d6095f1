#pragma once
// A world-space cache of irradiance E on the surfaces a view's probes see, shared by all of
// them: its cells, discovery, fill, direct light and lookups are docs/probes-estimator.md,
// "The radiance cache". Diffuse radiance leaving a point is f_d E, f_d = B (1 - M) / pi (eq. 13).
#include <array>
#include <atomic>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include <glm/glm.hpp>

#include "phyir/render/effects.h"
#include "phyir/render/direct_lighting.h"
#include "phyir/render/path_tracer.h"
#include "phyir/render/probe_settings.h"
#include "phyir/render/render_scene.h"
#include "sparse_cell_grid.h"

namespace phyir::render {

// A surface point as the cache sees it: normals on the side it was seen from.
struct CachePoint {
  glm::vec3 position{0.0f};
  glm::vec3 shading_normal{0.0f, 0.0f, 1.0f};
  glm::vec3 geometric_normal{0.0f, 0.0f, 1.0f};
};

// What a lookup returns. `direct` (the emissive triangles') and `punctual` (the punctual
// lights') are meaningful only when has_direct; their sum is the direct irradiance. The
// variances are those of the luminances of `indirect` and `direct` from the cells' fill noise
// (punctual light is exact); `block` names the cells whose noise the value shares (3 x 3 x 3,
// the smoothing's width; 0: none), docs/probes.md, "Per-texel standard error".
struct CachedIrradiance {
  glm::vec3 indirect{0.0f};
  glm::vec3 direct{0.0f};
  glm::vec3 punctual{0.0f};
  float indirect_variance = 0.0f;
  float direct_variance = 0.0f;
  uint64_t block = 0;
  bool has_direct = false;
};

class RadianceCache {
 public:
  static constexpr int kPointsPerCell = 8;

  // `path` = the view's path settings (max_bounces counted from a probe's first hit).
  RadianceCache(const RenderScene& scene, const Effects& effects, const PathSettings& path,
                const RadianceCacheSettings& settings);

  // Discovery, one per thread. `tie_break` must be a pure function of the sample that found
  // the point; each cell keeps its kPointsPerCell points nearest the centre, in any order.
  class Collector {
   public:
    void offer(const RadianceCache& cache, const CachePoint& point, uint64_t tie_break);

   private:
    friend class RadianceCache;
    struct Candidate {
      uint64_t priority;
      CachePoint point;
    };
    struct Best {
      int count = 0;
      Candidate kept[kPointsPerCell];  // the smallest priorities, unsorted
    };
    std::unordered_map<uint64_t, Best> cells_;
  };

  // Merges the collectors (only the set of offered points matters) and fills every cell in
  // parallel; rays go to `counters`.
  void build(const std::vector<const Collector*>& collectors, PathCounters* counters);

  // Irradiance at a point, interpolated between cells; when its own cell is unknown, a
  // one-sample estimate of the indirect part keyed by `key` (no direct part).
  CachedIrradiance lookup(const CachePoint& point, uint64_t key, PathCounters* counters) const;
  // The interpolation alone: false (and *out untouched) where the point's own cell is unknown.
  bool interpolate(const CachePoint& point, CachedIrradiance* out) const;

  // One estimate of the irradiance at `point` for cosine variate `u` and light variates
  // (u_select, u_light); the direct part only if `direct`.
  CachedIrradiance estimate(const CachePoint& point, const glm::vec2& u, bool direct, float u_select,
                            const glm::vec2& u_light, uint64_t key, PathCounters* counters) const;
  // The environment's own sample of an estimate's indirect E (MIS against its cosine ray).
  glm::vec3 environment_irradiance(const ShadingPoint& x, uint64_t key, PathCounters* counters) const;

  size_t cell_count() const { return cells_.size(); }
  uint64_t fill_samples() const { return fill_samples_; }
  size_t direct_cell_count() const { return direct_cells_; }
  // Mean luminance of the cells' irradiance (direct part where held): the view's brightness.
  float mean_irradiance_luminance() const;
  uint64_t fallbacks() const { return fallbacks_.load(); }
  const RadianceCacheSettings& settings() const { return settings_; }

 private:
  // A cell's points and, once filled, its irradiance (indirect its own mean, unsmoothed).
  struct Cell : CachedIrradiance {
    uint64_t key = 0;
    int count = 0;
    CachePoint points[kPointsPerCell];
  };
  // What a lookup reads of a cell, packed apart from the fill's points (cache lines).
  struct Value {
    glm::vec3 indirect, direct, punctual;
    float indirect_variance, direct_variance;
    bool has_direct;
  };
  // A cell's indirect light and the variance of its luminance.
  struct Smoothed {
    glm::vec3 indirect;
    float variance;
  };
  // A cell's 3 x 3 x 3 neighbourhood in its bucket: indices into cells_, -1 if absent, x-major.
  using Neighbours = std::array<int32_t, 27>;
  static int neighbour_slot(const glm::ivec3& offset) { return (offset.x + 1) * 9 + (offset.y + 1) * 3 + (offset.z + 1); }

  void fill(Cell* cell, PathCounters* counters) const;
  // Each cell's indirect light smoothed from its neighbours' means: their mean corrected by
  // a local linear fit's slopes, each kept by how far it stands out of the fill's noise.
  std::vector<Smoothed> smooth_indirect() const;
  // Cell i's smoothing as weights on its neighbours' means (they sum to 1).
  std::array<double, 27> smoothing_weights(size_t i) const;
  // The interpolation's weighted means of the corners present, into *out (block apart).
  void blend_corners(const std::array<const Value*, 8>& corners, const std::array<double, 8>& weights,
                     const Value& self, CachedIrradiance* out) const;
  // The 3 x 3 x 3 block of cells holding `cell`, as a key (> 0).
  static uint64_t block_of(const glm::ivec3& cell, int bucket);
  int find(uint64_t key) const;  // index into cells_, -1 if absent
  // Lattice coordinates (with the grid shift) of a position, in cells.
  glm::dvec3 lattice(const glm::vec3& position) const;
  static uint64_t pack(const glm::ivec3& cell, int bucket);
  static glm::ivec3 unpack(uint64_t key);  // pack's cell (as clamped there)

  const RenderScene* scene_;
  RadianceCacheSettings settings_;
  int max_bounces_;
  PathTracer tracer_;  // the paths after a cosine ray's hit (max_bounces - 1 of them)
  std::vector<Cell> cells_;  // sorted by key
  SparseCellGrid<int32_t> index_;  // cell -> index into cells_
  SparseCellGrid<Value> lookup_;  // what lookups read: the build's final values
  std::vector<Neighbours> neighbours_;  // per cell, as cells_
  size_t direct_cells_ = 0;
  uint64_t fill_samples_ = 0;
  mutable std::atomic<uint64_t> fallbacks_{0};
};

}  // namespace phyir::render
