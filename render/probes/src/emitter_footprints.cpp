#include "emitter_footprints.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>
#include <utility>
#include <vector>

#include "phyir/core/safe_math.h"
#include "phyir/render/equirect.h"

namespace phyir::render {

EmitterFootprints::EmitterFootprints(const scenes::Scene& scene) {
  for (const LightTriangle& t : light_triangles(scene)) triangles_.push_back(Triangle{t, {true, true, true}, {-1, -1, -1}});
  build_clusters();
  find_outlines();
}

void EmitterFootprints::find_outlines() {
  // Edges matched by position within a mesh: exporters split vertices along creases and seams.
  using Point = std::tuple<float, float, float>;
  using Edge = std::tuple<int, Point, Point>;
  auto edge = [](const Triangle& t, int e) {
    Point a{t.p[e].x, t.p[e].y, t.p[e].z}, b{t.p[(e + 1) % 3].x, t.p[(e + 1) % 3].y, t.p[(e + 1) % 3].z};
    if (b < a) std::swap(a, b);
    return Edge{t.mesh, a, b};
  };
  std::map<Edge, std::vector<int>> sides;
  for (size_t k = 0; k < triangles_.size(); ++k)
    for (int e = 0; e < 3; ++e) sides[edge(triangles_[k], e)].push_back(int(k));
  for (size_t k = 0; k < triangles_.size(); ++k) {
    Triangle& tri = triangles_[k];
    for (int e = 0; e < 3; ++e) {
      const std::vector<int>& s = sides[edge(tri, e)];
      if (s.size() != 2) continue;  // an open edge, or more than two sides: always the outline
      const int other = s[0] == int(k) ? s[1] : s[0];
      const Triangle& o = triangles_[size_t(other)];
      // Coplanar (a panel's diagonal): inside the light. A crease between consistently wound
      // sides (the edge reversed in the other): outline only where seen from opposite sides.
      bool consistent = false;
      for (int f = 0; f < 3; ++f)
        consistent |= o.p[f] == tri.p[(e + 1) % 3] && o.p[(f + 1) % 3] == tri.p[e];
      if (glm::dot(tri.normal, o.normal) > 0.999f) tri.outline[e] = false;
      else if (consistent) tri.across[e] = other;
    }
  }
}

namespace {

// Calls fn(uv) with the equirectangular position, seen from `origin`, of the points k / n of
// the edge a -> b, k = 0 .. n - 1 (and n too when `with_end`).
template <class Fn>
void for_edge_points(const glm::vec3& origin, const glm::vec3& a, const glm::vec3& b, int n, bool with_end, Fn fn) {
  for (int k = 0; k < n + (with_end ? 1 : 0); ++k) {
    const glm::vec3 d = glm::mix(a, b, float(k) / float(n)) - origin;
    const float len = glm::length(d);
    if (len > 0.0f) fn(equirect_uv(d / len));
  }
}

constexpr int kEdgeSamples = 16;  // points per edge for the box, at least, for the outline

}  // namespace

void EmitterFootprints::mark(const glm::vec3& origin, int h, int w, std::vector<uint8_t>* flags) const {
  for (const Cluster& c : clusters_) {
    if (!c.whole_light && mark_small_cluster(c, origin, h, w, flags)) continue;
    for (uint32_t k = c.first; k < c.first + c.count; ++k) {
      const Triangle& tri = triangles_[k];
      if (!tri.seen_from(origin)) continue;  // its back
      mark_box(tri, origin, h, w, flags);
      mark_outline(tri, origin, h, w, flags);
    }
  }
}

void EmitterFootprints::mark_box(const Triangle& tri, const glm::vec3& origin, int h, int w,
                                 std::vector<uint8_t>* flags) const {
  thread_local std::vector<float> us;
  us.clear();
  float vmin = 1.0f, vmax = 0.0f;
  for (int e = 0; e < 3; ++e)
    for_edge_points(origin, tri.p[e], tri.p[(e + 1) % 3], kEdgeSamples, false, [&](const glm::vec2& uv) {
      us.push_back(uv.x);
      vmin = std::min(vmin, uv.y);
      vmax = std::max(vmax, uv.y);
    });
  if (us.empty()) return;
  const bool up = surrounds(tri, origin, glm::vec3(0, 1, 0)), down = surrounds(tri, origin, glm::vec3(0, -1, 0));
  const int r0 = up ? 0 : std::max(int(vmin * h) - 1, 0);
  const int r1 = down ? h - 1 : std::min(int(vmax * h) + 1, h - 1);
  // The columns: the circle of u minus its largest empty gap.
  std::sort(us.begin(), us.end());
  float gap = us.front() + 1.0f - us.back();
  float start = us.front(), end = us.back();
  for (size_t k = 1; k < us.size(); ++k)
    if (us[k] - us[k - 1] > gap) gap = us[k] - us[k - 1], start = us[k], end = us[k - 1];
  int c0 = int(std::floor(start * w)) - 1, c1 = int(std::floor(end * w)) + 1;
  if (c1 < c0) c1 += w;
  const bool all_columns = up || down || c1 - c0 + 1 >= w;
  if (all_columns) c0 = 0, c1 = w - 1;
  for (int r = r0; r <= r1; ++r)
    for (int c = c0; c <= c1; ++c) {
      uint8_t& f = (*flags)[size_t(r) * w + size_t(((c % w) + w) % w)];
      f = std::max(f, kCovered);
    }
}

void EmitterFootprints::mark_outline(const Triangle& tri, const glm::vec3& origin, int h, int w,
                                     std::vector<uint8_t>* flags) const {
  // Points every 1/8 of a texel's height.
  for (int e = 0; e < 3; ++e) {
    if (!tri.outline[e]) continue;
    // Both sides of a crease seen from the same side (fronts, or backs of a two-sided light).
    if (tri.across[e] >= 0) {
      const Triangle& o = triangles_[size_t(tri.across[e])];
      const float a = glm::dot(tri.normal, origin - tri.p[0]), b = glm::dot(o.normal, origin - o.p[0]);
      if ((a > 0.0f && b > 0.0f) || (a < 0.0f && b < 0.0f && o.two_sided)) continue;
    }
    const glm::vec3& a = tri.p[e];
    const glm::vec3& b = tri.p[(e + 1) % 3];
    const float la = glm::length(a - origin), lb = glm::length(b - origin);
    if (!(la > 0.0f) || !(lb > 0.0f)) continue;
    const float angle = std::acos(std::clamp(glm::dot((a - origin) / la, (b - origin) / lb), -1.0f, 1.0f));
    const int n = std::clamp(int(std::ceil(angle / (kPi / float(h)) * 8.0f)), kEdgeSamples, 4096);
    for_edge_points(origin, a, b, n, true, [&](const glm::vec2& uv) {
      const int r = std::clamp(int(uv.y * float(h)), 0, h - 1), c = std::clamp(int(uv.x * float(w)), 0, w - 1);
      (*flags)[size_t(r) * w + size_t(c)] = kEdge;
    });
  }
}

bool EmitterFootprints::surrounds(const Triangle& t, const glm::vec3& o, const glm::vec3& d) {
  const glm::vec3 e1 = t.p[1] - t.p[0], e2 = t.p[2] - t.p[0];
  const glm::vec3 pv = glm::cross(d, e2);
  const float det = glm::dot(e1, pv);
  if (std::abs(det) < 1e-12f) return false;
  const glm::vec3 tv = o - t.p[0];
  const float a = glm::dot(tv, pv) / det;
  if (a < 0.0f || a > 1.0f) return false;
  const glm::vec3 qv = glm::cross(tv, e1);
  const float b = glm::dot(d, qv) / det;
  if (b < 0.0f || a + b > 1.0f) return false;
  return glm::dot(e2, qv) / det > 0.0f;
}

}  // namespace phyir::render
