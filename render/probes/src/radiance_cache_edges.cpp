// The radiance cache at concave edges (the header note of radiance_cache.h; docs/probes-estimator.md,
// "The radiance cache"): which cells lie next to one, where their points move to for the profile's
// bands, and the profile's difference at a lookup.
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "phyir/core/safe_math.h"
#include "radiance_cache.h"

namespace phyir::render {

namespace {

// Two surfaces closer to parallel than this (about 37 degrees) are one bent surface, not
// an edge.
constexpr float kMaxEdgeCosine = 0.8f;
// A cell's points are "in front of" another surface when their mean is this many cells off
// its plane: clear of a plane's rounding, well inside the thinnest layer that matters.
constexpr float kInFrontCells = 0.02f;
// A profile is kept when the cell's points lie between these distances from the edge (in
// cells): nearer, the cell already holds the light at the edge; further, it is not the
// layer next to the edge.
constexpr float kProfileMinCells = 0.1f;
constexpr float kProfileMaxCells = 1.5f;
// The bands' distances, as fractions of the cell points' distance: where the light falls
// fastest, near the edge, and half way.
constexpr float kBandFractions[2] = {1.0f / 6.0f, 0.5f};
// A moved point is on the surface if a ray dropped from this far above it (in cells)
// lands within kOnSurfaceCells of it, on a face turned as the original point's.
constexpr float kLiftCells = 0.1f;
constexpr float kOnSurfaceCells = 0.01f;
constexpr float kSameFaceCosine = 0.99f;
// Cells of a layer next to an edge are smoothed over this many cells each way along it:
// five in a row on a straight edge, as many estimates as the 3 x 3 neighbourhood of a
// flat surface at twice the fill, over 25 cm of an edge whose light changes over metres.
constexpr int kAlongEdgeCells = 2;

}  // namespace

int RadianceCache::facing_cell(size_t i, const std::vector<glm::vec3>& centre, const std::vector<glm::vec3>& normal,
                               float* distance_to_it) const {
  const Cell& cell = cells_[i];
  const glm::ivec3 at = unpack(cell.key);
  const glm::vec3& q = centre[i];
  const glm::vec3& nc = normal[i];
  const float in_front = kInFrontCells * settings_.cell_size;
  float nearest = std::numeric_limits<float>::infinity();
  int other = -1;
  for (int dx = -1; dx <= 1; ++dx)
    for (int dy = -1; dy <= 1; ++dy)
      for (int dz = -1; dz <= 1; ++dz) {
        // Every bucket of a position is one run of keys (the bucket is the low bits).
        const uint64_t first = pack(at + glm::ivec3(dx, dy, dz), 0);
        auto it = std::lower_bound(cells_.begin(), cells_.end(), first,
                                   [](const Cell& c, uint64_t key) { return c.key < key; });
        for (; it != cells_.end() && (it->key >> 6) == (first >> 6); ++it) {
          const size_t j = size_t(it - cells_.begin());
          if ((it->key & 63) == (cell.key & 63)) continue;
          const glm::vec3& no = normal[j];
          if (glm::dot(nc, no) > kMaxEdgeCosine) continue;
          if (glm::dot(centre[j] - q, nc) <= in_front) continue;  // convex, or behind
          const float distance = glm::dot(q - centre[j], no);
          if (distance <= in_front || distance >= nearest) continue;
          nearest = distance;
          other = int(j);
        }
      }
  *distance_to_it = nearest;
  return other;
}

void RadianceCache::find_concave_edges() {
  static_assert(sizeof(kBandFractions) / sizeof(kBandFractions[0]) == kEdgeBands, "one fraction per band");
  const size_t n = cells_.size();
  const float cell_size = settings_.cell_size;
  std::vector<glm::vec3> centre(n), normal(n);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 256), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t i = r.begin(); i < r.end(); ++i) {
      glm::vec3 p(0.0f), s(0.0f);
      for (int k = 0; k < cells_[i].count; ++k) {
        p += cells_[i].points[k].position;
        s += cells_[i].points[k].shading_normal;
      }
      centre[i] = p / float(std::max(cells_[i].count, 1));
      normal[i] = safe_normalize(s, cells_[i].points[0].shading_normal);
    }
  });

  std::vector<EdgeProfile> found(n);
  std::vector<char> has_profile(n, 0);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 64), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t i = r.begin(); i < r.end(); ++i) {
      Cell& cell = cells_[i];
      const glm::vec3& nc = normal[i];
      float nearest = 0.0f;
      const int other = facing_cell(i, centre, normal, &nearest);
      if (other < 0) continue;
      const glm::vec3& no = normal[size_t(other)];
      const glm::vec3 along = -(no - glm::dot(no, nc) * nc);
      const float length = glm::length(along);
      if (!(length > 0.3f)) continue;
      const glm::vec3 toward = along / length;
      // The layer next to the edge: no neighbour of its own bucket one cell towards it;
      // the second: one, which has none.
      const glm::vec3 a = glm::abs(toward);
      const int axis = (a.x >= a.y && a.x >= a.z) ? 0 : (a.y >= a.z ? 1 : 2);
      glm::ivec3 step(0);
      step[axis] = toward[axis] > 0.0f ? 1 : -1;
      const int inner = neighbours_[i][size_t(neighbour_slot(step))];
      if (inner >= 0) {
        if (neighbours_[size_t(inner)][size_t(neighbour_slot(step))] < 0) cell.edge_layer = 2;
        continue;
      }
      cell.edge_layer = 1;
      if (nearest < kProfileMinCells * cell_size || nearest > kProfileMaxCells * cell_size) continue;
      EdgeProfile& e = found[i];
      e.plane_point = centre[size_t(other)];
      e.plane_normal = no;
      e.toward = toward;
      e.centroid_distance = nearest;
      for (int b = 0; b < kEdgeBands; ++b) e.band_distance[size_t(b)] = kBandFractions[b] * nearest;
      has_profile[i] = 1;
    }
  });
  edges_.clear();
  for (size_t i = 0; i < n; ++i) {
    if (!has_profile[i]) continue;
    cells_[i].edge = int(edges_.size());
    edges_.push_back(found[i]);
  }
}

std::vector<int> RadianceCache::along_edge(size_t index) const {
  std::vector<int> out;
  const Cell& cell = cells_[index];
  const int bucket = int(cell.key & 63);
  const glm::ivec3 at = unpack(cell.key);
  const int r = kAlongEdgeCells;
  for (int dx = -r; dx <= r; ++dx)
    for (int dy = -r; dy <= r; ++dy)
      for (int dz = -r; dz <= r; ++dz) {
        const int other = find(pack(at + glm::ivec3(dx, dy, dz), bucket));
        if (other >= 0 && cells_[size_t(other)].edge_layer == cell.edge_layer) out.push_back(other);
      }
  return out;
}

bool RadianceCache::band_point(const EdgeProfile& edge, const CachePoint& point, int band, CachePoint* moved) const {
  const float cell_size = settings_.cell_size;
  const float distance = glm::dot(point.position - edge.plane_point, edge.plane_normal);
  const float rate = glm::dot(edge.toward, edge.plane_normal);  // < 0: nearer along `toward`
  if (!(rate < -0.3f)) return false;
  const float shift = (edge.band_distance[size_t(band)] - distance) / rate;
  if (!(std::abs(shift) < kProfileMaxCells * cell_size)) return false;
  const glm::vec3 target = point.position + shift * edge.toward;
  const float lift = kLiftCells * cell_size;
  Ray drop{target + lift * point.geometric_normal, -point.geometric_normal, 0.0f, 2.0f * lift};
  SurfaceInteraction si;
  if (!scene_->trace(drop, &si)) return false;
  if (!(std::abs(si.distance - lift) < kOnSurfaceCells * cell_size)) return false;
  if (!(glm::dot(si.geometric_normal, point.geometric_normal) > kSameFaceCosine)) return false;
  *moved = CachePoint{drop.origin + si.distance * drop.direction, point.shading_normal, point.geometric_normal};
  return true;
}

glm::vec3 RadianceCache::edge_difference(const EdgeProfile& edge, const glm::vec3& position) const {
  if (edge.band_pairs[0] == 0 || edge.band_pairs[1] == 0) return glm::vec3(0.0f);
  const float d = std::max(glm::dot(position - edge.plane_point, edge.plane_normal), 0.0f);
  const float c = edge.centroid_distance;
  if (d >= c) return glm::vec3(0.0f);
  const float b0 = edge.band_distance[0], b1 = edge.band_distance[1];
  const glm::vec3 &d0 = edge.band_delta[0], &d1 = edge.band_delta[1];
  // Linear between the knots (b0, d0), (b1, d1), (c, 0); nearer than b0, continued from
  // the first two (the light keeps falling towards the edge).
  if (d >= b1) return d1 * ((c - d) / (c - b1));
  if (d >= b0) return d0 + (d1 - d0) * ((d - b0) / (b1 - b0));
  return d0 + (d0 - d1) * ((b0 - d) / (b1 - b0));
}

}  // namespace phyir::render
