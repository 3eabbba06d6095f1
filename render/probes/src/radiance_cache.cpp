#include "radiance_cache.h"

#include <tbb/parallel_for.h>
#include <tbb/enumerable_thread_specific.h>

#include <algorithm>
#include <cmath>

#include "phyir/core/progress.h"
#include "phyir/core/safe_math.h"
#include "phyir/render/streams.h"

namespace phyir::render {

namespace {

// Cell coordinates are packed in 19 bits each (+-2^18 cells: +-13 km at 5 cm), the normal
// bucket in 6: 63 bits, so a key is exact and never equals the table's empty marker.
constexpr int kCoordBits = 19;
constexpr int64_t kCoordBias = int64_t(1) << (kCoordBits - 1);
constexpr uint64_t kCoordMask = (uint64_t(1) << kCoordBits) - 1;

// Shift the grid off round coordinates: a floor at y = 0 or a wall at x = 2 m on a cell
// boundary would be split between two layers of cells by rounding.
constexpr float kGridShift[3] = {0.1234567f, 0.3456789f, 0.2345678f};

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

// The integer cell of lattice coordinates, clamped far outside any packable range first.
glm::ivec3 cell_of(const glm::dvec3& c) {
  return glm::ivec3(glm::clamp(glm::floor(c), glm::dvec3(-1e9), glm::dvec3(1e9)));
}

}  // namespace

RadianceCache::RadianceCache(const RenderScene& scene, const Effects& effects, const PathSettings& path,
                             const RadianceCacheSettings& settings)
    : scene_(&scene),
      settings_(settings),
      max_bounces_(path.max_bounces),
      tracer_(scene, effects, path) {}

glm::dvec3 RadianceCache::lattice(const glm::vec3& position) const {
  glm::dvec3 c;
  for (int a = 0; a < 3; ++a) c[a] = double(position[a]) / settings_.cell_size + kGridShift[a];
  return c;
}

uint64_t RadianceCache::pack(const glm::ivec3& cell, int bucket) {
  uint64_t key = 0;
  for (int a = 0; a < 3; ++a) {
    const int64_t q = std::clamp<int64_t>(int64_t(cell[a]) + kCoordBias, 0, int64_t(kCoordMask));
    key = (key << kCoordBits) | uint64_t(q);
  }
  return (key << 6) | uint64_t(bucket);
}

glm::ivec3 RadianceCache::unpack(uint64_t key) {
  glm::ivec3 cell;
  for (int a = 0; a < 3; ++a) cell[a] = int(int64_t((key >> (6 + kCoordBits * (2 - a))) & kCoordMask) - kCoordBias);
  return cell;
}

void RadianceCache::Collector::offer(const RadianceCache& cache, const CachePoint& point, uint64_t tie_break) {
  // Nearest the centre, since lookups interpolate between centres (docs/probes-estimator.md,
  // "The radiance cache"). Priority: distance in 2^-20 cells in the high 32 bits, the
  // caller's hash below (ties, determinism).
  const glm::dvec3 c = cache.lattice(point.position);
  const glm::dvec3 offset = c - (glm::floor(c) + 0.5);  // within +-0.5 per axis
  const uint64_t distance = uint64_t(std::sqrt(glm::dot(offset, offset)) * double(1 << 20));
  const uint64_t priority = (distance << 32) | (tie_break >> 32);
  Best& best = cells_[pack(cell_of(c), normal_bucket(point.shading_normal))];
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
  // A grid over the cells holding value_of(i) for cell i.
  auto grid_of = [&](auto value_of) {
    using Grid = SparseCellGrid<decltype(value_of(size_t(0)))>;
    std::vector<typename Grid::Entry> entries;
    entries.reserve(cells_.size());
    for (size_t i = 0; i < cells_.size(); ++i)
      entries.push_back({unpack(cells_[i].key), int(cells_[i].key & 63), value_of(i)});
    return Grid(std::move(entries));
  };
  index_ = grid_of([](size_t i) { return int32_t(i); });

  neighbours_.resize(cells_.size());
  tbb::parallel_for(tbb::blocked_range<size_t>(0, cells_.size(), 256), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t i = r.begin(); i < r.end(); ++i) {
      const int bucket = int(cells_[i].key & 63);
      const glm::ivec3 at = unpack(cells_[i].key);
      for (int dx = -1; dx <= 1; ++dx)
        for (int dy = -1; dy <= 1; ++dy)
          for (int dz = -1; dz <= 1; ++dz) {
            const glm::ivec3 d(dx, dy, dz);
            neighbours_[i][size_t(neighbour_slot(d))] = find(pack(at + d, bucket));
          }
    }
  });

  tbb::enumerable_thread_specific<PathCounters> local;
  Progress progress("probe cache", cells_.size(), "cells", settings_.progress);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, cells_.size(), 16), [&](const tbb::blocked_range<size_t>& r) {
    PathCounters& c = local.local();
    for (size_t i = r.begin(); i < r.end(); ++i)
      fill(&cells_[i], &c);
    progress.advance(r.size());
  });
  for (const PathCounters& c : local) *counters += c;
  const std::vector<Smoothed> smoothed = settings_.smooth_indirect ? smooth_indirect() : std::vector<Smoothed>();
  lookup_ = grid_of([&](size_t i) {
    const Cell& cell = cells_[i];
    const Smoothed indirect = smoothed.empty() ? Smoothed{cell.indirect, cell.indirect_variance} : smoothed[i];
    return Value{indirect.indirect, cell.direct, cell.punctual, indirect.variance, cell.direct_variance, cell.has_direct};
  });
  direct_cells_ = size_t(std::count_if(cells_.begin(), cells_.end(), [](const Cell& c) { return c.has_direct; }));
  fill_samples_ = uint64_t(cells_.size()) * uint64_t(std::max(settings_.samples_per_cell, 1));
}

namespace {

glm::dvec3 neighbour_offset(int slot) { return glm::dvec3(slot / 9 - 1, (slot / 3) % 3 - 1, slot % 3 - 1); }

// The least-squares fit a + g . o over the present neighbours' offsets o (in cells): the rows
// of `slopes` give each axis's g as weights on the neighbours' values. Directions the offsets
// do not span (a flat surface's normal) keep no slope (the ridge).
void slope_weights(const std::array<int32_t, 27>& neighbours, std::array<std::array<double, 27>, 3>* slopes) {
  glm::dmat4 normal(0.0);
  for (int slot = 0; slot < 27; ++slot) {
    if (neighbours[size_t(slot)] < 0) continue;
    const glm::dvec4 x(1.0, neighbour_offset(slot));
    normal += glm::outerProduct(x, x);
  }
  for (int a = 1; a < 4; ++a) normal[a][a] += 1e-3;
  const glm::dmat4 inverse = glm::inverse(normal);  // symmetric: column k is row k
  for (int slot = 0; slot < 27; ++slot) {
    const glm::dvec4 x(1.0, neighbour_offset(slot));
    for (int a = 0; a < 3; ++a)
      (*slopes)[size_t(a)][size_t(slot)] = neighbours[size_t(slot)] < 0 ? 0.0 : glm::dot(x, inverse[a + 1]);
  }
}

}  // namespace

std::array<double, 27> RadianceCache::smoothing_weights(size_t i) const {
  const Neighbours& neighbours = neighbours_[i];
  std::array<double, 27> weights{};
  int count = 0;
  glm::dvec3 offset_mean(0.0);
  for (int slot = 0; slot < 27; ++slot)
    if (neighbours[size_t(slot)] >= 0) ++count, offset_mean += neighbour_offset(slot);
  offset_mean /= double(count);  // >= 1: the cell is its own neighbour
  for (int slot = 0; slot < 27; ++slot) weights[size_t(slot)] = neighbours[size_t(slot)] < 0 ? 0.0 : 1.0 / count;
  if (offset_mean == glm::dvec3(0.0)) return weights;  // neighbours all round: no slope moves the mean
  std::array<std::array<double, 27>, 3> slopes;
  slope_weights(neighbours, &slopes);
  for (int a = 0; a < 3; ++a) {
    // The fit's intercept is the mean less g . (the offsets' mean); each slope is kept by the
    // share 1 - var(g) / g^2 by which it stands out of the fill's noise.
    double g = 0.0, variance = 0.0;
    for (int slot = 0; slot < 27; ++slot) {
      if (neighbours[size_t(slot)] < 0) continue;
      const Cell& cell = cells_[size_t(neighbours[size_t(slot)])];
      const double m = slopes[size_t(a)][size_t(slot)];
      g += m * double(luminance(cell.indirect));
      variance += m * m * double(cell.indirect_variance);
    }
    const double kept = g * g > 0.0 ? std::max(0.0, 1.0 - variance / (g * g)) : 0.0;
    for (int slot = 0; slot < 27; ++slot) weights[size_t(slot)] -= kept * offset_mean[a] * slopes[size_t(a)][size_t(slot)];
  }
  return weights;
}

std::vector<RadianceCache::Smoothed> RadianceCache::smooth_indirect() const {
  std::vector<Smoothed> smoothed(cells_.size());
  tbb::parallel_for(tbb::blocked_range<size_t>(0, cells_.size(), 256), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t i = r.begin(); i < r.end(); ++i) {
      const std::array<double, 27> weights = smoothing_weights(i);
      glm::dvec3 sum(0.0);
      double variance = 0.0;  // the cells' fills are independent
      for (int slot = 0; slot < 27; ++slot) {
        const int index = neighbours_[i][size_t(slot)];
        if (index < 0) continue;
        sum += weights[size_t(slot)] * glm::dvec3(cells_[size_t(index)].indirect);
        variance += weights[size_t(slot)] * weights[size_t(slot)] * double(cells_[size_t(index)].indirect_variance);
      }
      smoothed[i] = Smoothed{glm::vec3(glm::max(sum, glm::dvec3(0.0))), float(variance)};
    }
  });
  return smoothed;
}

float RadianceCache::mean_irradiance_luminance() const {
  double sum = 0.0;
  for (const Cell& c : cells_) sum += double(luminance(c.indirect + (c.has_direct ? c.direct + c.punctual : glm::vec3(0.0f))));
  return cells_.empty() ? 0.0f : float(sum / double(cells_.size()));
}

int RadianceCache::find(uint64_t key) const {
  const int32_t* index = index_.find(unpack(key), int(key & 63));
  return index ? *index : -1;
}

CachedIrradiance RadianceCache::lookup(const CachePoint& point, uint64_t key, PathCounters* counters) const {
  CachedIrradiance out;
  if (interpolate(point, &out)) return out;
  fallbacks_.fetch_add(1, std::memory_order_relaxed);
  Rng rng = stream(key, Purpose::kCacheFallbackDirection);
  return estimate(point, rng.next_2d(), false, 0.0f, glm::vec2(0.0f), key, counters);
}

bool RadianceCache::interpolate(const CachePoint& point, CachedIrradiance* out) const {
  const int bucket = normal_bucket(point.shading_normal);
  const glm::dvec3 c = lattice(point.position);
  // Not finite, or beyond the grid's range: no cell holds the point.
  if (!glm::all(glm::lessThan(glm::abs(c), glm::dvec3(SparseCellGrid<Value>::kCoordLimit - 2)))) return false;
  // Linear between the centres of the 8 cells round the point, its own included; absent
  // ones (off the surface) left out.
  const glm::dvec3 t = c - 0.5;  // exact: |c| < 2^20
  const glm::dvec3 base = glm::floor(t), f = t - base;
  const glm::ivec3 first(base);
  // The point's own cell floor(c), relative to first: 1 on the axes where f >= 0.5.
  const glm::ivec3 own(f.x >= 0.5, f.y >= 0.5, f.z >= 0.5);
  std::array<double, 8> weights;
  std::array<bool, 8> wanted;
  for (int corner = 0; corner < 8; ++corner) {
    const glm::ivec3 d(corner & 1, (corner >> 1) & 1, (corner >> 2) & 1);
    weights[size_t(corner)] = (d.x ? f.x : 1.0 - f.x) * (d.y ? f.y : 1.0 - f.y) * (d.z ? f.z : 1.0 - f.z);
    wanted[size_t(corner)] = weights[size_t(corner)] > 0.0;
  }
  const std::array<const Value*, 8> corners = lookup_.corners(first, bucket, wanted);
  const Value* self = corners[size_t(own.x + 2 * own.y + 4 * own.z)];  // its weight is >= 1/8
  if (!self) return false;
  blend_corners(corners, weights, *self, out);
  out->block = block_of(first + own, bucket);
  return true;
}

void RadianceCache::blend_corners(const std::array<const Value*, 8>& corners, const std::array<double, 8>& weights,
                                  const Value& self, CachedIrradiance* out) const {
  // Variances: smoothed neighbours share most of their cells, so their errors are taken as one
  // (the weights' mean); unsmoothed, each corner's error is its own (sum of w^2 variance).
  const bool correlated = settings_.smooth_indirect;
  glm::dvec3 indirect(0.0), direct(0.0), punctual(0.0);
  double w_all = 0.0, w_direct = 0.0, indirect_variance = 0.0, direct_variance = 0.0;
  for (int corner = 0; corner < 8; ++corner) {
    const Value* cell = corners[size_t(corner)];
    if (!cell) continue;
    const double w = weights[size_t(corner)];
    indirect += w * glm::dvec3(cell->indirect);
    indirect_variance += (correlated ? w : w * w) * double(cell->indirect_variance);
    w_all += w;
    if (self.has_direct && cell->has_direct) {  // direct light is only used where the point's own cell holds it
      direct += w * glm::dvec3(cell->direct);
      punctual += w * glm::dvec3(cell->punctual);
      direct_variance += w * w * double(cell->direct_variance);
      w_direct += w;
    }
  }
  out->has_direct = self.has_direct;
  out->indirect = w_all > 0.0 ? glm::vec3(indirect / w_all) : self.indirect;
  out->indirect_variance =
      w_all > 0.0 ? float(indirect_variance / (correlated ? w_all : w_all * w_all)) : self.indirect_variance;
  out->direct = w_direct > 0.0 ? glm::vec3(direct / w_direct) : self.direct;
  out->punctual = w_direct > 0.0 ? glm::vec3(punctual / w_direct) : self.punctual;
  out->direct_variance = w_direct > 0.0 ? float(direct_variance / (w_direct * w_direct)) : self.direct_variance;
}

uint64_t RadianceCache::block_of(const glm::ivec3& cell, int bucket) {
  const glm::ivec3 block(glm::floor(glm::dvec3(cell) / 3.0));
  return pack(block, bucket);
}

}  // namespace phyir::render
