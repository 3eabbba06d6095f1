#include "phyir/insert/insert_scores.h"

#include <cmath>
#include <limits>

#include "phyir/core/error.h"

namespace phyir::insert {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

void check_sizes(const Image& a, const Image& b, const Image& region, const char* what) {
  if (a.width != b.width || a.height != b.height || region.width != a.width || region.height != a.height ||
      a.channels < 3 || b.channels < 3)
    fail("{}: images {}x{}x{} and {}x{}x{} and region {}x{} must be one size with three channels", what, a.width,
         a.height, a.channels, b.width, b.height, b.channels, region.width, region.height);
}

bool inside(const Image& region, int x, int y) { return region.at(x, y, 0) >= 0.5f; }

// eval's SSIM padding: columns wrap round the panorama, rows are replicated at the poles.
int wrap_column(int x, int w) { return ((x % w) + w) % w; }
int clamp_row(int y, int h) { return y < 0 ? 0 : (y >= h ? h - 1 : y); }

// SSIM at pixel (x, y), channel c: the Gaussian-weighted local statistics, computed directly
// (the region is a few hundred pixels; a full-image separable blur would cost more).
double ssim_at(const Image& a, const Image& b, int x, int y, int c, const std::vector<double>& g,
               const SsimWindow& w) {
  double ma = 0, mb = 0, aa = 0, bb = 0, ab = 0;
  for (int dy = -w.radius; dy <= w.radius; ++dy)
    for (int dx = -w.radius; dx <= w.radius; ++dx) {
      const int px = wrap_column(x + dx, a.width), py = clamp_row(y + dy, a.height);
      const double k = g[size_t(dx + w.radius)] * g[size_t(dy + w.radius)];
      const double u = a.at(px, py, c), v = b.at(px, py, c);
      ma += k * u, mb += k * v, aa += k * u * u, bb += k * v * v, ab += k * u * v;
    }
  const double sa = aa - ma * ma, sb = bb - mb * mb, sab = ab - ma * mb;
  return ((2 * ma * mb + w.c1) * (2 * sab + w.c2)) / ((ma * ma + mb * mb + w.c1) * (sa + sb + w.c2));
}

}  // namespace

double masked_rmse(const Image& a, const Image& b, const Image& region) {
  check_sizes(a, b, region, "masked RMSE");
  double sum = 0.0;
  size_t n = 0;
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x) {
      if (!inside(region, x, y)) continue;
      for (int c = 0; c < 3; ++c) sum += std::pow(double(a.at(x, y, c)) - double(b.at(x, y, c)), 2.0);
      n += 3;
    }
  return n ? std::sqrt(sum / double(n)) : kNaN;
}

double masked_ssim(const Image& a, const Image& b, const Image& region, const SsimWindow& w) {
  check_sizes(a, b, region, "masked SSIM");
  if (w.radius < 0 || !(w.sigma > 0.0)) fail("masked SSIM: bad window (radius {}, sigma {})", w.radius, w.sigma);
  std::vector<double> g(size_t(2 * w.radius + 1));
  double total = 0.0;
  for (int k = -w.radius; k <= w.radius; ++k) total += g[size_t(k + w.radius)] = std::exp(-k * k / (2 * w.sigma * w.sigma));
  for (double& v : g) v /= total;
  double sum = 0.0;
  size_t n = 0;
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x) {
      if (!inside(region, x, y)) continue;
      for (int c = 0; c < 3; ++c) sum += ssim_at(a, b, x, y, c, g, w);
      n += 3;
    }
  return n ? sum / double(n) : kNaN;
}

glm::dvec3 masked_mean(const Image& image, const Image& region) {
  glm::dvec3 sum(0.0);
  size_t n = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x)
      if (inside(region, x, y)) {
        for (int c = 0; c < 3; ++c) sum[c] += image.at(x, y, c);
        ++n;
      }
  return n ? sum / double(n) : glm::dvec3(0.0);
}

double change_error(const std::vector<glm::dvec3>& composite, const std::vector<glm::dvec3>& truth) {
  if (composite.size() != truth.size() || composite.size() < 2)
    fail("change error: {} composite frames and {} true frames (need the same number, at least 2)",
         composite.size(), truth.size());
  double sum = 0.0;
  for (size_t t = 1; t < truth.size(); ++t) {
    const glm::dvec3 d = (composite[t] - composite[t - 1]) - (truth[t] - truth[t - 1]);
    sum += glm::dot(d, d);
  }
  return std::sqrt(sum / (3.0 * double(truth.size() - 1)));
}

double rms_change(const std::vector<glm::dvec3>& frames) {
  return change_error(frames, std::vector<glm::dvec3>(frames.size(), glm::dvec3(0.0)));
}

ScoreSummary summarize(const std::vector<double>& scores) {
  ScoreSummary s;
  double sum = 0.0;
  for (double v : scores)
    if (!std::isnan(v)) sum += v, ++s.count;
  if (s.count == 0) return {kNaN, kNaN, 0};
  s.mean = sum / s.count;
  double ss = 0.0;
  for (double v : scores)
    if (!std::isnan(v)) ss += (v - s.mean) * (v - s.mean);
  s.sd = s.count > 1 ? std::sqrt(ss / (s.count - 1)) : 0.0;
  return s;
}

}  // namespace phyir::insert
