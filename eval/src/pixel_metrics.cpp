#include "phyir/eval/pixel_metrics.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "phyir/core/error.h"

namespace phyir::eval {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

void check_same(const Image& pred, const Image& gt, const Image& mask, const char* what) {
  if (pred.width != gt.width || pred.height != gt.height || pred.channels != gt.channels ||
      mask.width != gt.width || mask.height != gt.height)
    fail("{}: prediction {}x{}x{}, ground truth {}x{}x{}, mask {}x{} differ", what, pred.width, pred.height,
         pred.channels, gt.width, gt.height, gt.channels, mask.width, mask.height);
}

bool counted(const Image& mask, int x, int y) { return mask.at(x, y, 0) > 0.5f; }

}  // namespace

long count_mask(const Image& mask) {
  long n = 0;
  for (int y = 0; y < mask.height; ++y)
    for (int x = 0; x < mask.width; ++x) n += counted(mask, x, y);
  return n;
}

double masked_mse(const Image& pred, const Image& gt, const Image& mask) {
  check_same(pred, gt, mask, "masked_mse");
  double sum = 0.0;
  long n = 0;
  for (int y = 0; y < gt.height; ++y)
    for (int x = 0; x < gt.width; ++x) {
      if (!counted(mask, x, y)) continue;
      for (int c = 0; c < gt.channels; ++c) {
        const double d = double(pred.at(x, y, c)) - gt.at(x, y, c);
        sum += d * d;
        ++n;
      }
    }
  return n ? sum / n : kNaN;
}

double masked_mae(const Image& pred, const Image& gt, const Image& mask) {
  check_same(pred, gt, mask, "masked_mae");
  double sum = 0.0;
  long n = 0;
  for (int y = 0; y < gt.height; ++y)
    for (int x = 0; x < gt.width; ++x) {
      if (!counted(mask, x, y)) continue;
      for (int c = 0; c < gt.channels; ++c) {
        sum += std::abs(double(pred.at(x, y, c)) - gt.at(x, y, c));
        ++n;
      }
    }
  return n ? sum / n : kNaN;
}

double mean_angular_error_deg(const Image& pred, const Image& gt, const Image& mask) {
  check_same(pred, gt, mask, "mean_angular_error_deg");
  if (gt.channels != 3) fail("mean_angular_error_deg: normals need 3 channels, got {}", gt.channels);
  double sum = 0.0;
  long n = 0;
  for (int y = 0; y < gt.height; ++y)
    for (int x = 0; x < gt.width; ++x) {
      if (!counted(mask, x, y)) continue;
      double p[3], g[3], pp = 0, gg = 0, pg = 0;
      for (int c = 0; c < 3; ++c) {
        p[c] = pred.at(x, y, c);
        g[c] = gt.at(x, y, c);
        pp += p[c] * p[c];
        gg += g[c] * g[c];
        pg += p[c] * g[c];
      }
      double angle = 90.0;
      if (pp > 1e-20 && gg > 1e-20) {
        const double cosine = std::clamp(pg / std::sqrt(pp * gg), -1.0, 1.0);
        angle = std::acos(cosine) * 180.0 / M_PI;
      }
      sum += angle;
      ++n;
    }
  return n ? sum / n : kNaN;
}

DepthMetrics depth_metrics(const Image& pred, const Image& gt, const Image& mask) {
  check_same(pred, gt, mask, "depth_metrics");
  DepthMetrics m;
  double abs = 0, rel = 0, sqrel = 0, sq = 0, sqlog = 0, l10 = 0;
  long d1 = 0, d2 = 0, d3 = 0, n = 0;
  for (int y = 0; y < gt.height; ++y)
    for (int x = 0; x < gt.width; ++x) {
      const double g = gt.at(x, y, 0);
      if (!counted(mask, x, y) || !(g > 0.0)) continue;
      const double p = std::max(double(pred.at(x, y, 0)), double(kMinDepth));
      const double d = p - g;
      abs += std::abs(d);
      rel += std::abs(d) / g;
      sqrel += d * d / g;
      sq += d * d;
      const double dl = std::log(p) - std::log(g);
      sqlog += dl * dl;
      l10 += std::abs(std::log10(p) - std::log10(g));
      const double ratio = std::max(p / g, g / p);
      d1 += ratio < 1.25;
      d2 += ratio < 1.25 * 1.25;
      d3 += ratio < 1.25 * 1.25 * 1.25;
      ++n;
    }
  m.pixels = n;
  if (n == 0) {
    m.mae = m.abs_rel = m.sq_rel = m.rmse = m.rmse_log = m.log10 = m.delta1 = m.delta2 = m.delta3 = kNaN;
    return m;
  }
  m.mae = abs / n;
  m.abs_rel = rel / n;
  m.sq_rel = sqrel / n;
  m.rmse = std::sqrt(sq / n);
  m.rmse_log = std::sqrt(sqlog / n);
  m.log10 = l10 / n;
  m.delta1 = double(d1) / n;
  m.delta2 = double(d2) / n;
  m.delta3 = double(d3) / n;
  return m;
}

}  // namespace phyir::eval
