#include "phyir/render/radiance_cache.h"

#include <tbb/parallel_for.h>
#include <tbb/enumerable_thread_specific.h>

#include <algorithm>
#include <cmath>

#include "phyir/core/progress.h"
#include "phyir/core/safe_math.h"
#include "phyir/render/frame.h"
#include "phyir/render/probe_grid.h"
#include "phyir/render/ray_offset.h"
#include "phyir/render/rng.h"
#include "phyir/render/sampling.h"

namespace phyir::render {

namespace {

// Cell coordinates are packed in 19 bits each (+-2^18 cells: +-13 km at 5 cm), the normal
// bucket in 6: 63 bits, so a key is exact and never equals the table's empty marker.
constexpr int kCoordBits = 19;
constexpr int64_t kCoordBias = int64_t(1) << (kCoordBits - 1);
constexpr uint64_t kCoordMask = (uint64_t(1) << kCoordBits) - 1;
constexpr uint64_t kEmptySlot = ~uint64_t(0);

// The grid is shifted by these fractions of a cell so that surfaces at round coordinates
// (a floor at y = 0, walls at x = +-2 m) do not lie on cell boundaries, where rounding
// would split them between two layers of cells.
constexpr float kGridShift[3] = {0.1234567f, 0.3456789f, 0.2345678f};

// Purposes of the estimator's random streams (distinct from the path tracer's 1..5).
enum Purpose : uint64_t { kFallbackDirection = 102, kFillPermutation = 103 };

Rng purpose_rng(uint64_t key, Purpose purpose) { return Rng(mix64(key ^ mix64(purpose)), purpose); }

// Dominant axis and sign pick a cube face; the other two components, divided by the
// dominant one, pick one of 3 x 3 squares on it. 54 buckets of at most ~50 degrees.
int normal_bucket(const glm::vec3& n) {
  const glm::vec3 a = glm::abs(n);
  const int axis = (a.x >= a.y && a.x >= a.z) ? 0 : (a.y >= a.z ? 1 : 2);
  const float major = a[axis] > 0.0f ? a[axis] : 1.0f;
  const int sign = n[axis] < 0.0f ? 1 : 0;
  auto third = [](float t) { return std::clamp(int((t + 1.0f) * 1.5f), 0, 2); };
  const float s = n[(axis + 1) % 3] / major, t = n[(axis + 2) % 3] / major;
  return (axis * 2 + sign) * 9 + third(s) * 3 + third(t);
}

}  // namespace

RadianceCache::RadianceCache(const RenderScene& scene, const Effects& effects, const PathSettings& path,
                             const RadianceCacheSettings& settings)
    : scene_(&scene),
      settings_(settings),
      max_bounces_(path.max_bounces),
      continuation_(scene, effects, PathSettings{std::max(path.max_bounces - 1, 0), path.roulette_start}) {}

uint64_t RadianceCache::cell_key(const glm::vec3& position, const glm::vec3& normal) const {
  uint64_t key = 0;
  for (int a = 0; a < 3; ++a) {
    const double c = std::floor(double(position[a]) / settings_.cell_size + kGridShift[a]);
    const int64_t q = std::clamp<int64_t>(int64_t(std::clamp(c, -1e9, 1e9)) + kCoordBias, 0, int64_t(kCoordMask));
    key = (key << kCoordBits) | uint64_t(q);
  }
  return (key << 6) | uint64_t(normal_bucket(normal));
}

void RadianceCache::Collector::offer(const RadianceCache& cache, const CachePoint& point, uint64_t priority) {
  Best& best = cells_[cache.cell_key(point.position, point.shading_normal)];
  if (best.count < kPointsPerCell) {
    best.kept[best.count++] = Candidate{priority, point};
    return;
  }
  int worst = 0;
  for (int k = 1; k < kPointsPerCell; ++k)
    if (best.kept[k].priority > best.kept[worst].priority) worst = k;
  if (priority < best.kept[worst].priority) best.kept[worst] = Candidate{priority, point};
}

void RadianceCache::build(const std::vector<const Collector*>& collectors, PathCounters* counters) {
  // Merge: every candidate, sorted by (cell, priority); the first kPointsPerCell of each
  // cell are the set's smallest, whatever thread found them.
  std::vector<std::pair<uint64_t, Collector::Candidate>> all;
  for (const Collector* c : collectors)
    for (const auto& [key, best] : c->cells_)
      for (int k = 0; k < best.count; ++k) all.emplace_back(key, best.kept[k]);
  std::sort(all.begin(), all.end(), [](const auto& a, const auto& b) {
    return a.first != b.first ? a.first < b.first : a.second.priority < b.second.priority;
  });
  cells_.clear();
  for (const auto& [key, candidate] : all) {
    if (cells_.empty() || cells_.back().key != key) {
      cells_.emplace_back();
      cells_.back().key = key;
    }
    Cell& cell = cells_.back();
    if (cell.count < kPointsPerCell) cell.points[cell.count++] = candidate.point;
  }
  size_t capacity = 16;
  while (capacity < 2 * cells_.size()) capacity *= 2;
  table_.assign(capacity, {kEmptySlot, -1});
  for (size_t i = 0; i < cells_.size(); ++i) {
    size_t slot = mix64(cells_[i].key) & (capacity - 1);
    while (table_[slot].first != kEmptySlot) slot = (slot + 1) & (capacity - 1);
    table_[slot] = {cells_[i].key, int(i)};
  }

  tbb::enumerable_thread_specific<PathCounters> local;
  Progress progress("probe cache", cells_.size(), "cells", settings_.progress);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, cells_.size(), 16), [&](const tbb::blocked_range<size_t>& r) {
    PathCounters& c = local.local();
    for (size_t i = r.begin(); i < r.end(); ++i) fill(&cells_[i], &c);
    progress.advance(r.size());
  });
  for (const PathCounters& c : local) *counters += c;
}

const RadianceCache::Cell* RadianceCache::find(uint64_t key) const {
  if (table_.empty()) return nullptr;
  const size_t mask = table_.size() - 1;
  for (size_t slot = mix64(key) & mask;; slot = (slot + 1) & mask) {
    if (table_[slot].first == key) return &cells_[size_t(table_[slot].second)];
    if (table_[slot].first == kEmptySlot) return nullptr;
  }
}

void RadianceCache::fill(Cell* cell, PathCounters* counters) const {
  // samples_per_cell estimates shared out over the points, each point's own directions
  // stratified over the cosine-warped square.
  const int total = std::max(settings_.samples_per_cell, 1);
  glm::dvec3 sum(0.0);
  std::vector<glm::vec2> directions;
  int sample = 0;
  for (int k = 0; k < cell->count; ++k) {
    const int n = total / cell->count + (k < total % cell->count ? 1 : 0);
    Rng permutation = purpose_rng(mix64(settings_.seed ^ mix64(cell->key)) + uint64_t(k), kFillPermutation);
    stratified_square(n, permutation, &directions);
    for (const glm::vec2& u : directions) {
      const uint64_t key = PathTracer::path_key(settings_.seed, cell->key, uint64_t(sample++));
      sum += glm::dvec3(estimate(cell->points[k], u, key, counters));
    }
  }
  cell->irradiance = glm::vec3(sum / double(std::max(sample, 1)));
}

glm::vec3 RadianceCache::irradiance(const CachePoint& point, uint64_t key, PathCounters* counters) const {
  if (const Cell* cell = find(cell_key(point.position, point.shading_normal))) return cell->irradiance;
  fallbacks_.fetch_add(1, std::memory_order_relaxed);
  Rng rng = purpose_rng(key, kFallbackDirection);
  return estimate(point, rng.next_2d(), key, counters);
}

glm::vec3 RadianceCache::estimate(const CachePoint& point, const glm::vec2& u, uint64_t key,
                                  PathCounters* counters) const {
  // Indirect light only: what arrives from surfaces after scattering at least once (the
  // emission of the surface a direction hits is direct light, sampled per probe sample),
  // plus the environment. One cosine-distributed direction: cos / pdf = pi.
  if (max_bounces_ < 1) return glm::vec3(0.0f);  // nothing is reflected at all
  const RenderScene& scene = *scene_;
  const glm::vec3& ns = point.shading_normal;
  const glm::vec3& ng = point.geometric_normal;
  const Frame frame(ns);
  const glm::vec3 local = sample_cosine_hemisphere(u);
  const glm::vec3 wi = frame.to_world(local);
  if (!(local.z >= kMinCosine) || glm::dot(wi, ng) <= 0.0f) return glm::vec3(0.0f);
  const Ray ray{spawn_origin(point.position, ng, wi), wi};
  SurfaceInteraction si;
  ++counters->rays;
  glm::vec3 E(0.0f);
  if (!scene.trace(ray, &si)) {
    if (scene.environment()) E = kPi * scene.environment()->radiance(wi);
  } else if (max_bounces_ >= 2) {
    // The tracer adds its first hit's emission (this same si) at full weight: take it out.
    const glm::vec3 Le = si.emits ? si.emission : glm::vec3(0.0f);
    E = kPi * glm::max(continuation_.radiance(ray, key, counters) - Le, glm::vec3(0.0f));
  }
  if (!is_finite(E)) {
    ++counters->nonfinite_samples;
    return glm::vec3(0.0f);
  }
  return E;
}

}  // namespace phyir::render
