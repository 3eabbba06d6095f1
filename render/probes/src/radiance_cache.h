#pragma once
// A world-space cache of irradiance on the surfaces that a view's probes see: what makes
// every probe of a view share its light transport with the others (docs/probes-estimator.md).
//
// Cells. Space is cut into cubes of `cell_size`, and each cube's surface points are split
// by the direction of their shading normal (a cube face picked by the dominant axis, cut in
// 3 x 3, so flat walls at any axis-aligned orientation sit in the middle of one bucket):
// the two sides of a thin board, or a floor and the wall meeting it, never share a cell.
// Keys are packed exactly (no hash collisions). Lookups read the cells' values from a
// SparseCellGrid (4 x 4 x 4 cells per record): a lookup's 8 cells cost 1-2 table probes and
// sit close together in memory, where neighbouring probes' lookups find them again.
//
// Building. (1) Discovery: the probes' own first hits are offered to per-thread collectors;
// each cell keeps the kPointsPerCell points nearest its centre (ties broken by a hash of
// the sample that found them), so the kept set does not depend on thread count or order,
// and the cell's mean sits close to its centre, where lookups interpolate. (2) Fill: each
// cell's irradiance E = integral of L_i cos over the hemisphere of the shading normal is the
// mean of `samples_per_cell` one-sample estimates spread over its points (stratified
// cosine directions per point). E's first part is the INDIRECT light (plus the environment,
// also sampled by its own density: the sky through a window is a small bright patch):
// the radiance that the surface a cosine ray hits reflects, continued by the path tracer;
// the emission of that surface is direct light, kept apart (below). E counts paths of up to max_bounces - 1 further scattering events: a lookup at a
// probe's first hit (scattering event 0) gives exactly the path tracer's path lengths.
//
// Direct light. Cells far from every emitter (at least `direct_distance_cells` cell sizes
// from the nearest emitter's bounding box) also cache the direct irradiance: one light
// sample (shadow ray) per estimate, combined with the estimate's cosine ray by the power
// heuristic. Near an emitter direct irradiance changes too fast across a cell (the bright
// rim on a ceiling round a lamp), so there the probes keep sampling it per direction.
// Punctual lights (point, spot, sun) are kept apart: their light has hard shadow edges
// (a chair's legs under a lamp, a window's frame in the sun) that interpolation between
// cells blurs, and it is exact at a point for one shadow ray per light. So the sampled
// direct part is the emissive triangles' alone, and such cells hold the punctual lights'
// irradiance at their points exactly (`punctual`, the mean over the points), for lookups
// that end a path in the cache; a probe ray's own hit evaluates them itself.
//
// Smoothing. Indirect light comes from whole walls and changes over tens of centimetres,
// while a cell's fill noise is its own and is shared by every lookup of the cell (the
// ceiling 1 cm above a probe fills half of that probe's texels from a cell or two). So
// lookups read each cell's indirect value as the mean over its 3 x 3 x 3 neighbourhood of
// the same normal bucket: on a flat surface about 9 cells, a third of the noise, for a blur of one cell. Direct
// light, with its shadow edges, is not smoothed.
//
// Use. Outgoing diffuse radiance at a point is f_d E (f_d = B (1 - M) / pi, eq. 13), with B
// and M taken at the point itself (textures stay sharp). E is interpolated linearly between
// the centres of the point's cell and its neighbours of the same normal bucket (missing
// neighbours left out, weights renormalised): the cache's approximation is this spatial
// filter (error second order in cell size / distance to the light) and the fill's noise,
// shared by every lookup. A point whose own cell was never discovered gets a one-sample
// estimate of the indirect light instead (unbiased, noisy; counted as a fallback) and no
// direct light.
//
// Near a concave edge (a ceiling meeting a wall) irradiance falls in the last centimetres
// faster than cells follow, and the smoothing there is one-sided: the cache reads bright
// within a cell of the edge. Like every error of the cells' size it shrinks with them, and
// the passes of an error target shrink them (probe_pass_schedule.h).
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
// lights') are meaningful only when has_direct; their sum is the direct irradiance.
struct CachedIrradiance {
  glm::vec3 indirect{0.0f};
  glm::vec3 direct{0.0f};
  glm::vec3 punctual{0.0f};
  bool has_direct = false;
};

class RadianceCache {
 public:
  static constexpr int kPointsPerCell = 8;

  // `path` = the view's path settings (max_bounces counted from a probe's first hit).
  RadianceCache(const RenderScene& scene, const Effects& effects, const PathSettings& path,
                const RadianceCacheSettings& settings);

  // Discovery: one per thread; offer() points with a tie-break that is a pure function of
  // the sample that found them. Each cell keeps the kPointsPerCell points nearest its
  // centre (ties broken by the smaller tie-break), whatever order they come in.
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

  // Merges the collectors (the result depends only on the set of offered points) and fills
  // every cell in parallel. Rays go to `counters`.
  void build(const std::vector<const Collector*>& collectors, PathCounters* counters);

  // Irradiance at a point, interpolated between cells; when its own cell is unknown, a
  // one-sample estimate of the indirect part keyed by `key` (no direct part).
  CachedIrradiance lookup(const CachePoint& point, uint64_t key, PathCounters* counters) const;
  // The interpolation alone: false (and *out untouched) where the point's own cell is unknown.
  bool interpolate(const CachePoint& point, CachedIrradiance* out) const;

  // One estimate of the irradiance at `point` for cosine variate `u` and light variates
  // (u_select, u_light) (see the header note); the direct part only if `direct`.
  CachedIrradiance estimate(const CachePoint& point, const glm::vec2& u, bool direct, float u_select,
                            const glm::vec2& u_light, uint64_t key, PathCounters* counters) const;
  // The environment's share of an estimate's indirect irradiance from its own sample
  // (multiple importance against the estimate's cosine ray).
  glm::vec3 environment_irradiance(const ShadingPoint& x, uint64_t key, PathCounters* counters) const;
  // Stores a finite indirect estimate E in *out (counts a non-finite one) and returns *out.
  static CachedIrradiance finish_indirect(const glm::vec3& E, CachedIrradiance* out, PathCounters* counters);

  // The cell key of a point (position and shading normal).
  uint64_t cell_key(const glm::vec3& position, const glm::vec3& normal) const;

  size_t cell_count() const { return cells_.size(); }
  // Irradiance estimates the fill made.
  uint64_t fill_samples() const { return fill_samples_; }
  size_t direct_cell_count() const { return direct_cells_; }
  // The mean over cells of the luminance of the cached irradiance (direct part where held):
  // a scale of the view's brightness.
  float mean_irradiance_luminance() const;
  uint64_t fallbacks() const { return fallbacks_.load(); }
  const RadianceCacheSettings& settings() const { return settings_; }

 private:
  struct Cell {
    uint64_t key = 0;
    int count = 0;
    CachePoint points[kPointsPerCell];
    glm::vec3 indirect{0.0f};
    glm::vec3 direct{0.0f};
    glm::vec3 punctual{0.0f};
    bool has_direct = false;
  };
  // What a lookup reads of a cell, packed apart from the fill's points (cache lines).
  struct Value {
    glm::vec3 indirect{0.0f};
    glm::vec3 direct{0.0f};
    glm::vec3 punctual{0.0f};
    bool has_direct = false;
  };
  // A cell's 3 x 3 x 3 neighbourhood in its own normal bucket: indices into cells_, -1
  // where absent (x-major, each offset -1..1); the build's smoothing.
  using Neighbours = std::array<int32_t, 27>;
  static int neighbour_slot(const glm::ivec3& offset) { return (offset.x + 1) * 9 + (offset.y + 1) * 3 + (offset.z + 1); }

  void fill(Cell* cell, PathCounters* counters) const;
  // Each cell's indirect light smoothed from the cells' own means.
  std::vector<glm::vec3> smooth_indirect() const;
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
