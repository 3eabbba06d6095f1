#include "phyir/render/environment_portals.h"

#include <cmath>

#include "phyir/render/spherical_triangle.h"

namespace phyir::render {

namespace {

// The solid angle of triangle (p0, p1, p2) seen from x (Van Oosterom and Strackee 1983): one
// atan2, where SphericalTriangle::set also prepares sampling.
double triangle_solid_angle(const glm::vec3& x, const glm::vec3& p0, const glm::vec3& p1, const glm::vec3& p2) {
  const glm::dvec3 a = glm::dvec3(p0) - glm::dvec3(x), b = glm::dvec3(p1) - glm::dvec3(x), c = glm::dvec3(p2) - glm::dvec3(x);
  const double la = glm::length(a), lb = glm::length(b), lc = glm::length(c);
  const double numerator = std::abs(glm::dot(a, glm::cross(b, c)));
  const double denominator = la * lb * lc + glm::dot(a, b) * lc + glm::dot(a, c) * lb + glm::dot(b, c) * la;
  const double omega = 2.0 * std::atan2(numerator, denominator);
  return std::isfinite(omega) && omega > 0.0 ? omega : 0.0;
}

// The two triangles of a quad: (c, c + u, c + u + v) and (c, c + u + v, c + v).
double quad_triangle_solid_angle(const glm::vec3& x, const glm::vec3& c, const glm::vec3& u, const glm::vec3& v,
                                 int which) {
  return which == 0 ? triangle_solid_angle(x, c, c + u, c + u + v) : triangle_solid_angle(x, c, c + u + v, c + v);
}

bool set_triangle(SphericalTriangle* t, const glm::vec3& x, const glm::vec3& c, const glm::vec3& u, const glm::vec3& v,
                  int which) {
  return which == 0 ? t->set(x, c, c + u, c + u + v) : t->set(x, c, c + u + v, c + v);
}

}  // namespace

EnvironmentPortals::EnvironmentPortals(const std::vector<scenes::Portal>& portals) {
  for (const scenes::Portal& p : portals) {
    const glm::vec3 n = glm::cross(p.edge_u, p.edge_v);
    const float area = glm::length(n);
    if (!(area > 0.0f) || !std::isfinite(area)) continue;  // the loader refuses these; a generator bug should not crash
    portals_.push_back({p.corner, p.edge_u, p.edge_v, n / area});
  }
}

bool EnvironmentPortals::faces(const Quad& q, const glm::vec3& x) const {
  return glm::dot(x - q.corner, q.inward) > 0.0f;
}

bool EnvironmentPortals::passes_through(const Quad& q, const glm::vec3& x, const glm::vec3& direction) const {
  const float towards = glm::dot(direction, q.inward);
  if (!(towards < 0.0f) || !faces(q, x)) return false;
  const float t = glm::dot(q.corner - x, q.inward) / towards;
  const glm::vec3 d = x + t * direction - q.corner;
  // Coordinates along the (not necessarily orthogonal) edges: solve d = a u + b v.
  const float uu = glm::dot(q.edge_u, q.edge_u), uv = glm::dot(q.edge_u, q.edge_v), vv = glm::dot(q.edge_v, q.edge_v);
  const float du = glm::dot(d, q.edge_u), dv = glm::dot(d, q.edge_v);
  const float det = uu * vv - uv * uv;
  const float a = (du * vv - dv * uv) / det, b = (dv * uu - du * uv) / det;
  return a >= 0.0f && a <= 1.0f && b >= 0.0f && b <= 1.0f;
}

double EnvironmentPortals::solid_angle(const glm::vec3& x) const {
  double total = 0.0;
  for (const Quad& q : portals_)
    if (faces(q, x))
      for (int which = 0; which < 2; ++which) total += quad_triangle_solid_angle(x, q.corner, q.edge_u, q.edge_v, which);
  return total;
}

bool EnvironmentPortals::pick_triangle(const glm::vec3& x, double target, const Quad** quad, int* which) const {
  double below = 0.0;
  *quad = nullptr;
  for (const Quad& q : portals_) {
    if (!faces(q, x)) continue;
    for (int w = 0; w < 2; ++w) {
      const double omega = quad_triangle_solid_angle(x, q.corner, q.edge_u, q.edge_v, w);
      if (!(omega > 0.0)) continue;
      *quad = &q, *which = w;  // the last with any: where rounding puts target past the total
      if (target < below + omega) return true;
      below += omega;
    }
  }
  return *quad != nullptr;
}

bool EnvironmentPortals::sample(const glm::vec3& x, const glm::vec3& u, glm::vec3* direction, float* density) const {
  const double total = solid_angle(x);
  const Quad* q = nullptr;
  int which = 0;
  if (!(total > 0.0) || !pick_triangle(x, double(u.z) * total, &q, &which)) return false;
  SphericalTriangle t;
  if (!set_triangle(&t, x, q->corner, q->edge_u, q->edge_v, which)) return false;
  *direction = t.sample(glm::vec2(u.x, u.y));
  int through = 0;
  for (const Quad& p : portals_) through += passes_through(p, x, *direction) ? 1 : 0;
  *density = float(double(through) / total);
  return through > 0;  // a direction on a portal's rim may round outside it
}

float EnvironmentPortals::pdf(const glm::vec3& x, const glm::vec3& direction) const {
  int through = 0;
  for (const Quad& q : portals_) through += passes_through(q, x, direction) ? 1 : 0;
  if (through == 0) return 0.0f;
  const double total = solid_angle(x);
  return total > 0.0 ? float(double(through) / total) : 0.0f;
}

}  // namespace phyir::render
