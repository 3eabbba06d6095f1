#pragma once
// Pearson's chi-square goodness-of-fit test for direction samplers, after Mitsuba 3's
// mitsuba/python/chi2.py (ChiSquareTest): histogram the samples over a 2D parameter grid,
// integrate the claimed pdf over every cell, pool cells expected to hold fewer than 5
// samples, fail outright on samples in a cell of expected count 0, and turn the
// statistic into a p-value with the regularised upper incomplete gamma function.
//
// Significance: we reject at p < 1e-3. Mitsuba 3's run() defaults to 0.01 per test with
// a Sidak correction over the number of tests in a suite (1 - 0.99^(1/n)); with the ~10
// chi-square tests per suite here that is ~1e-3, so the two conventions agree.
//
// Header-only so any test in tests/render can use it; Debian's GoogleTest has no such
// helper and we do not want Boost just for gamma_q.
#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <numeric>
#include <sstream>
#include <string>
#include <vector>

#include "phyir/core/safe_math.h"
#include "phyir/render/frame.h"

namespace phyir::test {

// Regularised lower incomplete gamma P(a, x) by its power series; converges fast for
// x < a + 1 (Numerical Recipes 6.2, gser).
inline double gamma_p_series(double a, double x) {
  double ap = a, sum = 1.0 / a, del = sum;
  for (int n = 0; n < 100000; ++n) {
    ap += 1.0;
    del *= x / ap;
    sum += del;
    if (std::abs(del) < std::abs(sum) * 1e-15) break;
  }
  return sum * std::exp(-x + a * std::log(x) - std::lgamma(a));
}

// Regularised upper incomplete gamma Q(a, x) by its continued fraction (modified Lentz);
// converges fast for x >= a + 1 (Numerical Recipes 6.2, gcf).
inline double gamma_q_fraction(double a, double x) {
  constexpr double kTiny = 1e-300;
  double b = x + 1.0 - a, c = 1.0 / kTiny, d = 1.0 / b, h = d;
  for (int i = 1; i < 100000; ++i) {
    const double an = -i * (i - a);
    b += 2.0;
    d = an * d + b;
    if (std::abs(d) < kTiny) d = kTiny;
    c = b + an / c;
    if (std::abs(c) < kTiny) c = kTiny;
    d = 1.0 / d;
    const double del = d * c;
    h *= del;
    if (std::abs(del - 1.0) < 1e-15) break;
  }
  return std::exp(-x + a * std::log(x) - std::lgamma(a)) * h;
}

// Q(a, x) = Gamma(a, x) / Gamma(a), for a > 0, x >= 0.
inline double gamma_q(double a, double x) {
  if (x <= 0.0) return 1.0;
  if (x < a + 1.0) return 1.0 - gamma_p_series(a, x);
  return gamma_q_fraction(a, x);
}

// P(X >= chi2) for X ~ chi-square with `dof` degrees of freedom.
inline double chi_square_p_value(double chi2, int dof) { return gamma_q(0.5 * dof, 0.5 * chi2); }

struct ChiSquareResult {
  double statistic = 0.0;
  int dof = 0;
  double p_value = 0.0;
  int pooled_cells = 0;       // cells merged because their expected count was < 5
  int impossible_samples = 0;  // samples in cells of expected count 0 (fails the test)
  std::string message;

  bool passed(double significance = 1e-3) const {
    return impossible_samples == 0 && dof >= 1 && std::isfinite(p_value) &&
           p_value >= significance;
  }
};

// observed[i] and expected[i] are counts over the same cells, which must cover all
// outcomes (add a cell for "sample rejected" if the sampler can fail).
inline ChiSquareResult chi_square_test(const std::vector<double>& observed,
                                       const std::vector<double>& expected,
                                       double min_expected = 5.0) {
  ChiSquareResult r;
  const size_t n = observed.size();
  std::vector<size_t> order(n);
  std::iota(order.begin(), order.end(), size_t{0});
  std::sort(order.begin(), order.end(),
            [&](size_t a, size_t b) { return expected[a] < expected[b]; });
  // Mitsuba's pooling: walk cells by increasing expected count, accumulating the small
  // ones until the pool reaches min_expected; each full pool counts as one cell.
  double pool_obs = 0.0, pool_exp = 0.0;
  int cells = 0, pool_size = 0;
  for (size_t idx : order) {
    const double e = expected[idx], o = observed[idx];
    if (e <= 0.0) {
      if (o > 0.0) r.impossible_samples += static_cast<int>(o);
      continue;
    }
    if (e < min_expected) {
      pool_obs += o;
      pool_exp += e;
      ++pool_size;
      ++r.pooled_cells;
      if (pool_exp >= min_expected) {
        r.statistic += (pool_obs - pool_exp) * (pool_obs - pool_exp) / pool_exp;
        ++cells;
        pool_obs = pool_exp = 0.0;
        pool_size = 0;
      }
      continue;
    }
    r.statistic += (o - e) * (o - e) / e;
    ++cells;
  }
  if (pool_size > 0 && pool_exp > 0.0) {  // a last, still small pool
    r.statistic += (pool_obs - pool_exp) * (pool_obs - pool_exp) / pool_exp;
    ++cells;
  }
  r.dof = cells - 1;
  r.p_value = r.dof >= 1 ? chi_square_p_value(r.statistic, r.dof) : 0.0;
  std::ostringstream os;
  os << "chi2 = " << r.statistic << ", dof = " << r.dof << ", p = " << r.p_value
     << ", pooled cells = " << r.pooled_cells
     << ", samples in zero-probability cells = " << r.impossible_samples;
  r.message = os.str();
  return r;
}

// Midpoint-rule quadrature over a grid's [0,1]^2 parameter domain, shared by the grids
// below. A Grid has nx(), ny(), cells() and direction(x, y, &jacobian), the Jacobian
// being dOmega / (dx dy).
template <typename Grid, typename Fn>
void for_each_grid_point(const Grid& grid, int sub, Fn&& fn) {
  const int nx = grid.nx(), ny = grid.ny();
  const double hx = 1.0 / (double(nx) * sub), hy = 1.0 / (double(ny) * sub);
  for (int iy = 0; iy < ny; ++iy) {
    for (int ix = 0; ix < nx; ++ix) {
      for (int sy = 0; sy < sub; ++sy) {
        for (int sx = 0; sx < sub; ++sx) {
          double jac = 0.0;
          const glm::vec3 w = grid.direction((ix * sub + sx + 0.5) * hx, (iy * sub + sy + 0.5) * hy, &jac);
          fn(iy * nx + ix, w, jac * hx * hy);
        }
      }
    }
  }
}

// Per-cell integrals of f (returning double or glm::dvec3) on sub x sub points per cell.
template <typename T = double, typename Grid, typename Fn>
std::vector<T> integrate_grid_cells(const Grid& grid, Fn&& f, int sub) {
  std::vector<T> out(grid.cells(), T(0.0));
  for_each_grid_point(grid, sub, [&](int c, const glm::vec3& w, double weight) { out[c] += T(f(w)) * weight; });
  return out;
}

template <typename T = double, typename Grid, typename Fn>
T integrate_grid(const Grid& grid, Fn&& f, int sub) {
  T sum(0.0);
  for_each_grid_point(grid, sub, [&](int, const glm::vec3& w, double weight) { sum += T(f(w)) * weight; });
  return sum;
}

// A parameterisation of the sphere by [0,1]^2 about an axis: theta' = pi x^power from the
// axis, phi' = 2 pi y around it. power = 1 with axis +z is the plain (theta, phi) grid;
// power > 1 packs cells near the axis, to resolve a narrow lobe centred on it.
class SphereGrid {
 public:
  SphereGrid(const glm::vec3& axis, float power, int nx, int ny)
      : frame_(axis), power_(power), nx_(nx), ny_(ny) {}

  int cells() const { return nx_ * ny_; }
  int nx() const { return nx_; }
  int ny() const { return ny_; }

  // The direction at parameter (x, y) and dOmega / (dx dy) there.
  glm::vec3 direction(double x, double y, double* jacobian) const {
    const double theta = kPiD * std::pow(x, static_cast<double>(power_));
    const double phi = 2.0 * kPiD * y;
    const double st = std::sin(theta);
    if (jacobian) {
      const double dtheta_dx =
          kPiD * power_ * (power_ == 1.0f ? 1.0 : std::pow(x, static_cast<double>(power_) - 1.0));
      *jacobian = st * dtheta_dx * 2.0 * kPiD;
    }
    const glm::vec3 local(static_cast<float>(st * std::cos(phi)),
                          static_cast<float>(st * std::sin(phi)),
                          static_cast<float>(std::cos(theta)));
    return frame_.to_world(local);
  }

  // The cell a direction falls in, or -1 for a degenerate direction.
  int cell(const glm::vec3& w) const {
    const glm::vec3 l = frame_.to_local(w);
    const double len = std::sqrt(double(l.x) * l.x + double(l.y) * l.y + double(l.z) * l.z);
    if (!(len > 0.0)) return -1;
    // atan2 of the in-plane length keeps full precision near the axis, unlike acos.
    const double theta = std::atan2(std::sqrt(double(l.x) * l.x + double(l.y) * l.y), double(l.z));
    double phi = std::atan2(double(l.y), double(l.x));
    if (phi < 0.0) phi += 2.0 * kPiD;
    const double x = std::pow(theta / kPiD, 1.0 / power_);
    const double y = phi / (2.0 * kPiD);
    const int ix = std::clamp(static_cast<int>(x * nx_), 0, nx_ - 1);
    const int iy = std::clamp(static_cast<int>(y * ny_), 0, ny_ - 1);
    return iy * nx_ + ix;
  }

  // Calls fn(cell, direction, quadrature weight) for the midpoint rule on sub x sub points
  // per cell; the weights include the Jacobian, so they sum to 4 pi.
  template <typename Fn>
  void for_each_point(int sub, Fn&& fn) const {
    for_each_grid_point(*this, sub, fn);
  }

  // Integral of f over every cell by the midpoint rule on sub x sub points.
  std::vector<double> integrate_cells(const std::function<double(const glm::vec3&)>& f,
                                      int sub) const {
    return integrate_grid_cells<double>(*this, f, sub);
  }

  double integrate(const std::function<double(const glm::vec3&)>& f, int sub) const {
    return integrate_grid<double>(*this, f, sub);
  }

 private:
  static constexpr double kPiD = 3.14159265358979323846;
  render::Frame frame_;
  float power_;
  int nx_, ny_;
};

// The upper hemisphere (local frame, z = normal) as a (theta, phi) grid whose cells are
// packed around a lobe centre (theta_c, phi_c) with angular scales `width_theta` (along
// theta) and `width_side` (across, i.e. sin(theta) dphi):
//   theta = theta_c + w sinh(A + (B - A) x),  phi = phi_c + w_phi sinh(A' + (B' - A') y),
// with A, B chosen so x in [0,1] spans theta in [0, acos(z_min)] (and y spans phi_c -+ pi).
// Cells are ~w wide at the centre and grow geometrically away from it, so one grid
// resolves a lobe of any width, and the cut-off z = z_min (the horizon, or a BRDF's
// kMinCosine) is the edge x = 1, never inside a cell: integrands that jump there (a pdf)
// are integrated as accurately as smooth ones. (A jump inside a cell is not: a pdf of 2.7
// per unit z cut at z = 1e-4 put a 2.7e-4 error into its integral at any affordable grid.)
class LobeGrid {
 public:
  LobeGrid(const glm::vec3& centre, double width_theta, double width_side, int nx, int ny,
           double z_min = 0.0)
      : nx_(nx), ny_(ny), z_min_(z_min), theta_max_(std::acos(std::clamp(z_min, 0.0, 1.0))) {
    theta_c_ = std::atan2(std::hypot(double(centre.x), double(centre.y)), double(centre.z));
    theta_c_ = std::clamp(theta_c_, 0.0, theta_max_);
    phi_c_ = std::atan2(double(centre.y), double(centre.x));
    w_theta_ = std::max(width_theta, 1e-7);
    // A lobe of angular width w across spans w / sin(theta) in phi; around the pole phi
    // does not matter (the lobe is a disc in theta).
    const double side = std::max(width_side, 1e-7);
    w_phi_ = std::min(side / std::max(std::sin(theta_c_), w_theta_), kPiD);
    a_theta_ = std::asinh((0.0 - theta_c_) / w_theta_);
    b_theta_ = std::asinh((theta_max_ - theta_c_) / w_theta_);
    a_phi_ = std::asinh(-kPiD / w_phi_);
    b_phi_ = std::asinh(kPiD / w_phi_);
  }

  int cells() const { return nx_ * ny_; }
  int nx() const { return nx_; }
  int ny() const { return ny_; }

  glm::vec3 direction(double x, double y, double* jacobian) const {
    const double tx = a_theta_ + (b_theta_ - a_theta_) * x;
    const double ty = a_phi_ + (b_phi_ - a_phi_) * y;
    const double theta = std::clamp(theta_c_ + w_theta_ * std::sinh(tx), 0.0, theta_max_);
    const double phi = phi_c_ + w_phi_ * std::sinh(ty);
    const double st = std::sin(theta);
    if (jacobian) {
      *jacobian = st * (w_theta_ * (b_theta_ - a_theta_) * std::cosh(tx)) *
                  (w_phi_ * (b_phi_ - a_phi_) * std::cosh(ty));
    }
    return glm::vec3(static_cast<float>(st * std::cos(phi)), static_cast<float>(st * std::sin(phi)),
                     static_cast<float>(std::cos(theta)));
  }

  // The cell of a direction, or -1 below z_min (or degenerate).
  int cell(const glm::vec3& w) const {
    if (!(double(w.z) >= z_min_)) return -1;
    const double theta = std::atan2(std::hypot(double(w.x), double(w.y)), double(w.z));
    double dphi = std::atan2(double(w.y), double(w.x)) - phi_c_;
    while (dphi > kPiD) dphi -= 2.0 * kPiD;
    while (dphi < -kPiD) dphi += 2.0 * kPiD;
    const double x = (std::asinh((theta - theta_c_) / w_theta_) - a_theta_) / (b_theta_ - a_theta_);
    const double y = (std::asinh(dphi / w_phi_) - a_phi_) / (b_phi_ - a_phi_);
    const int ix = std::clamp(static_cast<int>(x * nx_), 0, nx_ - 1);
    const int iy = std::clamp(static_cast<int>(y * ny_), 0, ny_ - 1);
    return iy * nx_ + ix;
  }

 private:
  static constexpr double kPiD = 3.14159265358979323846;
  int nx_, ny_;
  double z_min_, theta_max_;
  double theta_c_ = 0.0, phi_c_ = 0.0, w_theta_ = 1.0, w_phi_ = 1.0;
  double a_theta_ = 0.0, b_theta_ = 1.0, a_phi_ = 0.0, b_phi_ = 1.0;
};

// Runs a chi-square test of a direction sampler against its pdf over `grid`.
// `sample(i, &w, &is_delta)` draws sample i (from its own fixed-seed stream) and returns
// false when the sampler rejects it. Rejected samples are not histogrammed (the pdf
// integrates to 1 minus their probability, as in Mitsuba where they carry weight 0); the
// result reports how many there were and how many the pdf predicts, n (1 - integral), so
// the caller can check the rejection rate separately with a quadrature tolerance (the
// chi-square statistic cannot absorb quadrature error in a cell expecting ~0 samples).
// A sample outside the grid's domain (LobeGrid: below z_min) counts as a sample in a cell
// of expected count 0 and fails the test.
// `delta_probability` > 0 adds a cell for delta samples (`sample` sets *is_delta).
struct DirectionChiSquare : ChiSquareResult {
  double rejected_observed = 0.0;
  double rejected_expected = 0.0;
};

template <typename Grid>
DirectionChiSquare chi_square_directions(
    const Grid& grid, int n, const std::function<bool(int, glm::vec3*, bool*)>& sample,
    const std::function<double(const glm::vec3&)>& pdf, int sub = 8,
    double delta_probability = 0.0) {
  // Cells: the grid's, then one for delta samples, then one (expected 0) for samples
  // outside the grid.
  std::vector<double> observed(grid.cells() + 2, 0.0);
  const int kDelta = grid.cells(), kOutside = grid.cells() + 1;
  double rejected = 0.0;
  for (int i = 0; i < n; ++i) {
    glm::vec3 w(0.0f);
    bool is_delta = false;
    if (!sample(i, &w, &is_delta)) {
      rejected += 1.0;
    } else if (is_delta) {
      observed[kDelta] += 1.0;
    } else {
      const int c = grid.cell(w);
      observed[c < 0 ? kOutside : c] += 1.0;
    }
  }
  std::vector<double> expected = integrate_grid_cells<double>(grid, pdf, sub);
  double total = 0.0;
  for (double& e : expected) {
    e *= n;
    total += e;
  }
  expected.push_back(n * delta_probability);
  expected.push_back(0.0);
  DirectionChiSquare r;
  static_cast<ChiSquareResult&>(r) = chi_square_test(observed, expected);
  r.rejected_observed = rejected;
  r.rejected_expected = n * (1.0 - delta_probability) - total;
  std::ostringstream os;
  os << r.message << "; rejected samples: observed " << r.rejected_observed
     << ", expected " << r.rejected_expected;
  r.message = os.str();
  return r;
}

}  // namespace phyir::test
