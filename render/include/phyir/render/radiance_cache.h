#pragma once
// A world-space cache of irradiance on the surfaces that a view's probes see: what makes
// every probe of a view share its light transport with the others (docs/probes.md).
//
// Cells. Space is cut into cubes of `cell_size`, and each cube's surface points are split
// by the direction of their shading normal (a cube face picked by the dominant axis, cut in
// 3 x 3, so flat walls at any axis-aligned orientation sit in the middle of one bucket):
// the two sides of a thin board, or a floor and the wall meeting it, never share a cell.
// Keys are packed exactly (no hash collisions), in a read-only open-addressing table.
//
// Building. (1) Discovery: the probes' own first hits are offered to per-thread collectors;
// each cell keeps the kPointsPerCell points of smallest priority (a hash of the sample that
// found them), so the kept set does not depend on thread count or order. (2) Fill: each
// cell's irradiance E = integral of L_i cos over the hemisphere of the shading normal is the
// mean of `samples_per_cell` one-sample estimates spread over its points (stratified
// cosine directions per point). E holds the INDIRECT light only (plus the environment):
// the radiance that the surface a cosine ray hits reflects, continued by the path tracer;
// the emission of that surface is direct light, which the probes sample per direction
// (probe_renderer.h), so the cache never blurs a shadow edge or the bright rim around a
// light. E counts paths of up to max_bounces - 1 further scattering events: a lookup at a
// probe's first hit (scattering event 0) gives exactly the path tracer's path lengths.
//
// Use. Outgoing indirect diffuse radiance at a point is f_d E (f_d = B (1 - M) / pi, eq. 13), with B
// and M taken at the point itself (textures stay sharp). The cache's approximation is the
// spatial one: E is averaged over the cell's points (a cell_size-wide box filter over the
// surface); noise is the fill's, shared by every lookup. A point whose cell was never
// discovered gets a one-sample estimate instead (unbiased, noisy; counted as a fallback).
#include <atomic>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include <glm/glm.hpp>

#include "phyir/render/effects.h"
#include "phyir/render/path_tracer.h"
#include "phyir/render/render_scene.h"

namespace phyir::render {

struct RadianceCacheSettings {
  float cell_size = 0.05f;    // metres
  int samples_per_cell = 128;  // irradiance estimates per cell
  uint64_t seed = 0;
  bool progress = false;
};

// A surface point as the cache sees it: normals on the side it was seen from.
struct CachePoint {
  glm::vec3 position{0.0f};
  glm::vec3 shading_normal{0.0f, 0.0f, 1.0f};
  glm::vec3 geometric_normal{0.0f, 0.0f, 1.0f};
};

class RadianceCache {
 public:
  static constexpr int kPointsPerCell = 8;

  // `path` = the view's path settings (max_bounces counted from a probe's first hit).
  RadianceCache(const RenderScene& scene, const Effects& effects, const PathSettings& path,
                const RadianceCacheSettings& settings);

  // Discovery: one per thread; offer() points with a priority that is a pure function of
  // the sample that found them.
  class Collector {
   public:
    void offer(const RadianceCache& cache, const CachePoint& point, uint64_t priority);

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

  // Irradiance at a point: its cell's, or a one-sample estimate keyed by `key` when the
  // cell is unknown.
  glm::vec3 irradiance(const CachePoint& point, uint64_t key, PathCounters* counters) const;

  // One estimate of the irradiance at `point` for cosine variate `u` (see the header note).
  glm::vec3 estimate(const CachePoint& point, const glm::vec2& u, uint64_t key, PathCounters* counters) const;

  // The cell key of a point (position and shading normal).
  uint64_t cell_key(const glm::vec3& position, const glm::vec3& normal) const;

  size_t cell_count() const { return cells_.size(); }
  uint64_t fill_samples() const { return uint64_t(cells_.size()) * settings_.samples_per_cell; }
  uint64_t fallbacks() const { return fallbacks_.load(); }
  const RadianceCacheSettings& settings() const { return settings_; }

 private:
  struct Cell {
    uint64_t key = 0;
    int count = 0;
    CachePoint points[kPointsPerCell];
    glm::vec3 irradiance{0.0f};
  };
  void fill(Cell* cell, PathCounters* counters) const;
  const Cell* find(uint64_t key) const;

  const RenderScene* scene_;
  RadianceCacheSettings settings_;
  int max_bounces_;
  PathTracer continuation_;  // max_bounces - 1: the paths after a cosine ray's hit
  std::vector<Cell> cells_;  // sorted by key
  std::vector<std::pair<uint64_t, int>> table_;  // open addressing, power-of-two size
  mutable std::atomic<uint64_t> fallbacks_{0};
};

}  // namespace phyir::render
