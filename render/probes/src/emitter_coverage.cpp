#include "emitter_coverage.h"

#include <algorithm>
#include <cmath>

#include "phyir/core/safe_math.h"

namespace phyir::render {

namespace {

// Outline points of an edge spanning pi (a light's solid angle within ~1e-4). A chord's error
// goes as angle / points^2 times the map's 1 / sin(theta) stretch, hence sqrt(a / pi) / sin(theta)
// (theta at the end nearer a pole); docs/probes-estimator.md, "Lights seen directly".
constexpr int kArcPoints = 96;
constexpr int kMinArcPoints = 4;
// Largest phi step between outline points (steps halved near a pole): keeps unwrapping unambiguous.
constexpr double kMaxPhiStep = 0.05;
constexpr int kMaxHalvings = 30;
// Longer outlines give up (plain estimate): an arc skirting a pole could make 2^30 points.
constexpr size_t kMaxOutlinePoints = 4096;
// More light triangles (real furniture's lamp shades) trace no coverage: a probe sees them all.
constexpr size_t kMaxTracedTriangles = 4096;

// phi of the equirectangular map (equirect.cpp): 0 towards -Z, increasing towards +X.
double phi_of(const glm::dvec3& d) { return std::atan2(d.x, -d.z); }

// Whether unit u is off the poles' axis, where phi is defined (squared: hypot is slow here).
bool off_pole_axis(const glm::dvec3& u) { return u.x * u.x + u.z * u.z > 1e-24; }

int arc_points(const glm::dvec3& a, const glm::dvec3& b) {
  const double angle = std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b));
  const glm::dvec3 ua = glm::normalize(a), ub = glm::normalize(b);
  const double sin_theta = std::sqrt(std::min(ua.x * ua.x + ua.z * ua.z, ub.x * ub.x + ub.z * ub.z));
  const double points = kArcPoints * std::sqrt(std::max(angle, 0.0) / kPi) / std::max(sin_theta, 1e-3);
  return int(std::clamp(std::ceil(points), double(kMinArcPoints), double(kArcPoints)));
}

// Appends the arc from a (already in `out`, at unwrapped `phi_a`) to b, b included, halving
// steps that turn more than kMaxPhiStep. False through a pole (phi undefined there).
bool append_arc(const glm::dvec3& a, double phi_a, const glm::dvec3& b, int depth, std::vector<glm::dvec2>* out,
                double* phi_end) {
  const glm::dvec3 u = glm::normalize(b);
  if (!off_pole_axis(u)) return false;
  double phi = phi_of(u);
  phi += kTwoPi * std::round((phi_a - phi) / kTwoPi);
  if (out->size() >= kMaxOutlinePoints) return false;
  if (std::abs(phi - phi_a) > kMaxPhiStep) {
    if (depth >= kMaxHalvings) return false;
    const glm::dvec3 m = 0.5 * (a + b);
    double phi_m = 0.0;
    return append_arc(a, phi_a, m, depth + 1, out, &phi_m) && append_arc(m, phi_m, b, depth + 1, out, phi_end);
  }
  out->push_back({phi, u.y});
  *phi_end = phi;
  return true;
}

// Area and bounding box of closed polygon `poly` clipped to [x0, x1] x [y0, y1] (Sutherland-
// Hodgman, then shoelace; a concave polygon's zero-width bridges along the sides add no area).
double clipped_area(const std::vector<glm::dvec2>& poly, double x0, double x1, double y0, double y1, glm::dvec2* lo,
                    glm::dvec2* hi) {
  thread_local std::vector<glm::dvec2> a, b;
  // One side of the box: the part of `in` on its inner side, into *out.
  auto clip = [](const std::vector<glm::dvec2>& in, std::vector<glm::dvec2>* out, int axis, double bound,
                 bool keep_above) {
    out->clear();
    auto inside = [&](const glm::dvec2& p) { return keep_above ? p[axis] >= bound : p[axis] <= bound; };
    for (size_t i = 0, n = in.size(); i < n; ++i) {
      const glm::dvec2& p = in[i];
      const glm::dvec2& q = in[i + 1 < n ? i + 1 : 0];
      const bool pin = inside(p), qin = inside(q);
      if (pin) out->push_back(p);
      if (pin != qin) {
        const double t = (bound - p[axis]) / (q[axis] - p[axis]);
        out->push_back(p + t * (q - p));
      }
    }
  };
  clip(poly, &a, 0, x0, true);
  clip(a, &b, 0, x1, false);
  clip(b, &a, 1, y0, true);
  clip(a, &b, 1, y1, false);
  double twice = 0.0;
  *lo = glm::dvec2(x1, y1), *hi = glm::dvec2(x0, y0);
  for (size_t i = 0, n = b.size(); i < n; ++i) {
    const glm::dvec2& p = b[i];
    const glm::dvec2& q = b[i + 1 < n ? i + 1 : 0];
    twice += p.x * q.y - q.x * p.y;
    *lo = glm::min(*lo, p), *hi = glm::max(*hi, p);
  }
  return 0.5 * std::abs(twice);
}

}  // namespace

EmitterCoverage::EmitterCoverage(const scenes::Scene& scene) : triangles_(light_triangles(scene)) {
  usable_ = !triangles_.empty() && triangles_.size() <= kMaxTracedTriangles &&
            std::all_of(triangles_.begin(), triangles_.end(), [](const LightTriangle& t) { return t.uniform; });
}

EmitterCoverage::View EmitterCoverage::view(const glm::vec3& origin) const {
  View v;
  if (!usable_) {
    v.valid_ = false;
    return v;
  }
  for (const LightTriangle& tri : triangles_) {
    if (!tri.seen_from(origin)) continue;
    View::Seen s;
    s.emission = tri.emission;
    glm::dvec3 d[3];
    for (int k = 0; k < 3; ++k) d[k] = glm::dvec3(tri.p[k]) - glm::dvec3(origin);
    // Inside the spherical triangle: on the inner side of the three great circles.
    const double orientation = glm::dot(d[0], glm::cross(d[1], d[2]));
    if (!(std::abs(orientation) > 0.0)) continue;  // seen edge-on
    for (int e = 0; e < 3; ++e)
      s.edge_normal[e] = glm::vec3(glm::cross(d[e], d[(e + 1) % 3]) * (orientation > 0.0 ? 1.0 : -1.0));
    s.to_plane = glm::vec3(d[0]);
    s.plane_normal = tri.normal;
    // The outline in (phi unwrapped, cos theta), from d[0] round to d[0] again.
    const glm::dvec3 u0 = glm::normalize(d[0]);
    if (!off_pole_axis(u0)) {
      v.valid_ = false;
      return v;
    }
    const double start = phi_of(u0);
    s.outline.push_back({start, u0.y});
    double phi = start;
    for (int e = 0; e < 3; ++e) {
      const int points = arc_points(d[e], d[(e + 1) % 3]);
      for (int k = 1; k <= points; ++k) {
        const glm::dvec3 a = glm::mix(d[e], d[(e + 1) % 3], double(k - 1) / points);
        const glm::dvec3 b = glm::mix(d[e], d[(e + 1) % 3], double(k) / points);
        if (!append_arc(a, phi, b, 0, &s.outline, &phi)) {
          v.valid_ = false;
          return v;
        }
      }
    }
    // Back at d[0]: a turn of 2 pi means the triangle surrounds a pole; close the outline
    // along that pole's line (cos theta = +-1).
    if (std::abs(phi - start) > 1.0) {
      const double z = v.inside(s, glm::vec3(0.0f, 1.0f, 0.0f)) ? 1.0 : -1.0;
      s.outline.push_back({phi, z});
      s.outline.push_back({start, z});
    }
    s.phi_min = s.phi_max = s.outline.front().x;
    s.z_min = s.z_max = s.outline.front().y;
    for (const glm::dvec2& q : s.outline) {
      s.phi_min = std::min(s.phi_min, q.x), s.phi_max = std::max(s.phi_max, q.x);
      s.z_min = std::min(s.z_min, q.y), s.z_max = std::max(s.z_max, q.y);
    }
    v.seen_.push_back(std::move(s));
  }
  return v;
}

void EmitterCoverage::View::texel_pieces(int row, int col, int h, int w, std::vector<Piece>* pieces) const {
  pieces->clear();
  const double z0 = std::cos(kPi * double(row + 1) / h), z1 = std::cos(kPi * double(row) / h);
  const double p0 = (double(col) / w - 0.5) * kTwoPi, p1 = (double(col + 1) / w - 0.5) * kTwoPi;
  const double area = (p1 - p0) * (z1 - z0);
  for (size_t i = 0; i < seen_.size(); ++i) {
    const Seen& s = seen_[i];
    if (s.z_max < z0 || s.z_min > z1) continue;
    // The outline's phi is unwrapped: try the texel at every turn it may overlap.
    for (int k = -2; k <= 2; ++k) {
      const double q0 = p0 + k * kTwoPi, q1 = p1 + k * kTwoPi;
      if (s.phi_max < q0 || s.phi_min > q1) continue;
      Piece piece;
      piece.fraction = std::min(clipped_area(s.outline, q0, q1, z0, z1, &piece.lo, &piece.hi) / area, 1.0);
      if (!(piece.fraction > 0.0)) continue;
      piece.light = int(i);
      piece.emission = s.emission;
      pieces->push_back(piece);
    }
  }
}

glm::vec3 EmitterCoverage::View::texel_mean(int row, int col, int h, int w) const {
  thread_local std::vector<Piece> pieces;
  texel_pieces(row, col, h, w, &pieces);
  glm::dvec3 sum(0.0);
  for (const Piece& piece : pieces) sum += glm::dvec3(piece.emission) * piece.fraction;
  return glm::vec3(sum);
}

bool EmitterCoverage::View::hits(int light, const glm::vec3& d, float* distance) const {
  const Seen& s = seen_[size_t(light)];
  if (!inside(s, d)) return false;
  const float toward = glm::dot(d, s.plane_normal);
  if (!(std::abs(toward) > 1e-12f)) return false;  // edge-on: no area to hit
  *distance = glm::dot(s.to_plane, s.plane_normal) / toward;
  return *distance > 0.0f && std::isfinite(*distance);
}

}  // namespace phyir::render
