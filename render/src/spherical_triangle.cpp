#include "phyir/render/spherical_triangle.h"

#include <algorithm>
#include <cmath>

namespace phyir::render {

namespace {

bool unit(const glm::dvec3& v, glm::dvec3* out) {
  const double length = glm::length(v);
  if (!(length > 0.0) || !std::isfinite(length)) return false;
  *out = v / length;
  return true;
}

// The interior angle at vertex v between the arcs towards p and q: the angle between the
// planes (v, p) and (v, q).
double corner_angle(const glm::dvec3& v, const glm::dvec3& p, const glm::dvec3& q) {
  glm::dvec3 np, nq;
  if (!unit(glm::cross(v, p), &np) || !unit(glm::cross(v, q), &nq)) return 0.0;
  return std::acos(std::clamp(glm::dot(np, nq), -1.0, 1.0));
}

// w with its component along unit u removed, normalised (u itself if nothing is left).
glm::dvec3 orthogonal_part(const glm::dvec3& w, const glm::dvec3& u) {
  glm::dvec3 out;
  return unit(w - glm::dot(w, u) * u, &out) ? out : u;
}

}  // namespace

bool SphericalTriangle::set(const glm::vec3& reference, const glm::vec3& p0, const glm::vec3& p1,
                            const glm::vec3& p2) {
  const glm::dvec3 r(reference);
  if (!unit(glm::dvec3(p0) - r, &a_) || !unit(glm::dvec3(p1) - r, &b_) || !unit(glm::dvec3(p2) - r, &c_)) return false;
  alpha_ = corner_angle(a_, b_, c_);  // the one angle sample() needs
  // Van Oosterom and Strackee (1983): tan(omega / 2) = |a.(b x c)| / (1 + a.b + b.c + c.a) for
  // unit a, b, c. One atan2 instead of Girard's three corner angles, whose sum minus pi cancels.
  const double triple = std::abs(glm::dot(a_, glm::cross(b_, c_)));
  solid_angle_ = 2.0 * std::atan2(triple, 1.0 + glm::dot(a_, b_) + glm::dot(b_, c_) + glm::dot(c_, a_));
  return solid_angle_ > 0.0 && std::isfinite(solid_angle_);
}

glm::vec3 SphericalTriangle::sample(const glm::vec2& u) const {
  // Arvo's two steps: u.x picks the sub-triangle (a, b, c_hat) of area u.x x the whole,
  // whose third vertex c_hat lies on the arc from a to c; u.y then picks a point on the arc
  // from b to c_hat, uniformly in the cosine of its distance from b.
  const double area = double(u.x) * solid_angle_;
  const double s = std::sin(area - alpha_), t = std::cos(area - alpha_);
  const double cos_alpha = std::cos(alpha_), sin_alpha = std::sin(alpha_);
  const double cos_c = glm::dot(a_, b_);  // the arc between a and b
  const double uu = t - cos_alpha, vv = s + sin_alpha * cos_c;
  const double denominator = (vv * s + uu * t) * sin_alpha;
  const double q = denominator != 0.0 ? std::clamp(((vv * t - uu * s) * cos_alpha - vv) / denominator, -1.0, 1.0) : 1.0;
  const glm::dvec3 c_hat = q * a_ + std::sqrt(std::max(0.0, 1.0 - q * q)) * orthogonal_part(c_, a_);
  const double z = std::clamp(1.0 - double(u.y) * (1.0 - glm::dot(c_hat, b_)), -1.0, 1.0);
  const glm::dvec3 d = z * b_ + std::sqrt(std::max(0.0, 1.0 - z * z)) * orthogonal_part(c_hat, b_);
  return glm::vec3(glm::normalize(d));
}

}  // namespace phyir::render
