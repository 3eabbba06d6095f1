#include "phyir/insert/insert_scores.h"

#include <cmath>
#include <limits>

#include "phyir/core/error.h"
#include "phyir/eval/pixel_metrics.h"
#include "phyir/eval/ssim.h"

namespace phyir::insert {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

void check_sizes(const Image& a, const Image& b, const Image& region, const char* what) {
  if (a.width != b.width || a.height != b.height || region.width != a.width || region.height != a.height ||
      a.channels < 3 || b.channels < 3)
    fail("{}: images {}x{}x{} and {}x{}x{} and region {}x{} must be one size with three channels", what, a.width,
         a.height, a.channels, b.width, b.height, b.channels, region.width, region.height);
}

bool inside(const Image& region, int x, int y) { return region.at(x, y, 0) > 0.5f; }

}  // namespace

double masked_rmse(const Image& a, const Image& b, const Image& region) {
  check_sizes(a, b, region, "masked RMSE");
  return std::sqrt(eval::masked_mse(a, b, region));
}

double masked_ssim(const Image& a, const Image& b, const Image& region) {
  check_sizes(a, b, region, "masked SSIM");
  eval::SsimOptions options;
  options.region = &region;
  return eval::ssim(a, b, options);
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
