// EmitterFootprints' clusters: nearby light triangles marked together when they are far.
#include <algorithm>
#include <cmath>

#include "emitter_footprints.h"
#include "phyir/core/safe_math.h"
#include "phyir/render/equirect.h"

namespace phyir::render {

namespace {

glm::vec3 centroid(const LightTriangle& t) { return (t.p[0] + t.p[1] + t.p[2]) / 3.0f; }

}  // namespace

void EmitterFootprints::build_clusters() {
  // Meshes first, so that a cluster never mixes two lights.
  std::stable_sort(triangles_.begin(), triangles_.end(),
                   [](const Triangle& a, const Triangle& b) { return a.mesh < b.mesh; });
  auto split = [&](auto&& self, uint32_t first, uint32_t count, bool whole_light) -> void {
    glm::vec3 lo(INFINITY), hi(-INFINITY);
    for (uint32_t k = first; k < first + count; ++k)
      for (const glm::vec3& p : triangles_[k].p) lo = glm::min(lo, p), hi = glm::max(hi, p);
    if (count <= kClusterSize) {
      Cluster c{(lo + hi) * 0.5f, 0.0f, first, count, whole_light};
      for (uint32_t k = first; k < first + count; ++k)
        for (const glm::vec3& p : triangles_[k].p) c.radius = std::max(c.radius, glm::length(p - c.center));
      clusters_.push_back(c);
      return;
    }
    const glm::vec3 extent = hi - lo;
    const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
    const uint32_t half = count / 2;
    std::nth_element(triangles_.begin() + first, triangles_.begin() + first + half, triangles_.begin() + first + count,
                     [axis](const Triangle& a, const Triangle& b) { return centroid(a)[axis] < centroid(b)[axis]; });
    self(self, first, half, false);
    self(self, first + half, count - half, false);
  };
  for (uint32_t first = 0; first < triangles_.size();) {
    uint32_t end = first;
    while (end < triangles_.size() && triangles_[end].mesh == triangles_[first].mesh) ++end;
    split(split, first, end - first, true);
    first = end;
  }
}

bool EmitterFootprints::mark_small_cluster(const Cluster& c, const glm::vec3& origin, int h, int w,
                                           std::vector<uint8_t>* flags) const {
  const glm::vec3 to_center = c.center - origin;
  const float distance = glm::length(to_center);
  if (!(distance > c.radius)) return false;  // inside its sphere
  const float cap = std::asin(std::min(c.radius / distance, 1.0f));  // the sphere's angular radius
  if (cap > kPi / float(h)) return false;                              // wider than a texel is high
  const glm::vec2 uv = equirect_uv(to_center / distance);
  const float theta = uv.y * kPi;
  // The cap is exact (no sampled points, unlike a triangle's box): no margin.
  const int r0 = std::max(int(std::floor((theta - cap) / kPi * float(h))), 0);
  const int r1 = std::min(int(std::floor((theta + cap) / kPi * float(h))), h - 1);
  // The cap's half-width in longitude is widest on its row nearest a pole; a cap over a pole
  // takes every column.
  const float pole_distance = std::min(theta, kPi - theta) - cap;
  const float half_width =
      pole_distance > 0.0f ? std::asin(std::min(std::sin(cap) / std::sin(pole_distance), 1.0f)) : kPi;
  int c0 = int(std::floor((uv.x - half_width / (2.0f * kPi)) * float(w)));
  int c1 = int(std::floor((uv.x + half_width / (2.0f * kPi)) * float(w)));
  if (half_width >= kPi || c1 - c0 + 1 >= w) c0 = 0, c1 = w - 1;
  for (int r = r0; r <= r1; ++r)
    for (int col = c0; col <= c1; ++col) (*flags)[size_t(r) * w + size_t(((col % w) + w) % w)] = kEdge;
  return true;
}

}  // namespace phyir::render
