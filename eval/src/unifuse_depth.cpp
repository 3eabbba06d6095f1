#include "phyir/eval/unifuse_depth.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "phyir/core/error.h"

namespace phyir::eval {
namespace {

// The counted pixels after UniFuse's clamps, in its order: gt and pred raised to 0.1, then
// gt lowered to 10 where gt > 10, then where pred > 10.
struct ClampedPixels {
  std::vector<float> gt, pred;
};

ClampedPixels clamped_pixels(const Image& pred, const Image& gt) {
  ClampedPixels c;
  for (size_t i = 0; i < gt.pixels.size(); ++i) {
    float g = gt.pixels[i], p = pred.pixels[i];
    if (!unifuse_counts(g)) continue;
    if (g < kUnifuseMinDepth) g = kUnifuseMinDepth;
    if (p < kUnifuseMinDepth) p = kUnifuseMinDepth;
    if (g > kUnifuseMaxDepth) g = kUnifuseMaxDepth;
    if (p > kUnifuseMaxDepth) g = kUnifuseMaxDepth;  // UniFuse writes gt here, not pred
    c.gt.push_back(g);
    c.pred.push_back(p);
  }
  return c;
}

// torch.median: the lower of the two middle values for an even count.
float lower_median(std::vector<float> v) {
  const auto middle = v.begin() + std::ptrdiff_t((v.size() - 1) / 2);
  std::nth_element(v.begin(), middle, v.end());
  return *middle;
}

void align_medians(ClampedPixels& c) {
  const float scale = lower_median(c.gt) / lower_median(c.pred);  // float32, as the tensors
  for (float& p : c.pred) p *= scale;
}

DepthMetrics reduce(const ClampedPixels& c) {
  double abs = 0, rel = 0, sqrel = 0, sq = 0, sqlog = 0, l10 = 0;
  long d1 = 0, d2 = 0, d3 = 0;
  for (size_t i = 0; i < c.gt.size(); ++i) {
    const double g = c.gt[i], p = c.pred[i], d = g - p;
    abs += std::abs(d);
    rel += std::abs(d) / g;
    sqrel += d * d / g;
    sq += d * d;
    const double dl = std::log10(g) - std::log10(p);
    sqlog += dl * dl;
    l10 += std::abs(std::log10(p / g));
    const double ratio = std::max(g / p, p / g);
    d1 += ratio < 1.25;
    d2 += ratio < 1.25 * 1.25;
    d3 += ratio < 1.25 * 1.25 * 1.25;
  }
  DepthMetrics m;
  const long n = long(c.gt.size());
  m.pixels = n;
  const double mean = n ? 1.0 / double(n) : std::numeric_limits<double>::quiet_NaN();
  m.mae = abs * mean, m.abs_rel = rel * mean, m.sq_rel = sqrel * mean;
  m.rmse = std::sqrt(sq * mean), m.rmse_log = std::sqrt(sqlog * mean), m.log10 = l10 * mean;
  m.delta1 = double(d1) * mean, m.delta2 = double(d2) * mean, m.delta3 = double(d3) * mean;
  return m;
}

}  // namespace

bool unifuse_counts(float gt) { return gt > 0.0f && gt <= kUnifuseMaxDepth; }  // NaN fails both

DepthMetrics unifuse_depth_metrics(const Image& pred, const Image& gt, bool median_align) {
  if (pred.width != gt.width || pred.height != gt.height || pred.channels != 1 || gt.channels != 1)
    fail("unifuse_depth_metrics: prediction {}x{}x{} and ground truth {}x{}x{} must be one channel of one size",
         pred.width, pred.height, pred.channels, gt.width, gt.height, gt.channels);
  ClampedPixels c = clamped_pixels(pred, gt);
  if (median_align && !c.gt.empty()) align_medians(c);
  return reduce(c);
}

}  // namespace phyir::eval
