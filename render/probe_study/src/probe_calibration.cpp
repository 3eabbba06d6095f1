#include "phyir/render/probe_calibration.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "phyir/core/error.h"
#include "phyir/core/safe_math.h"

namespace phyir::render {

namespace {

constexpr double kGaussianMedianAbs = 0.6745;  // median of |N(0, 1)|

float texel_luminance(const Image& image, int x, int y) {
  return luminance(glm::vec3(image.at(x, y, 0), image.at(x, y, 1), image.at(x, y, 2)));
}

}  // namespace

nlohmann::json ProbeCalibration::to_json() const {
  const auto number = [](double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); };
  return {{"median_ratio", number(median_ratio)}, {"within_two_sigma", number(within_two_sigma)}, {"texels", texels}};
}

ProbeCalibration probe_calibration(const Image& value, const Image& value_stderr, const Image& reference,
                                   const Image& reference_stderr) {
  for (const Image* image : {&value_stderr, &reference, &reference_stderr})
    if (image->width != value.width || image->height != value.height)
      fail("probe calibration: images of {}x{} and {}x{}", value.width, value.height, image->width, image->height);
  std::vector<double> ratios;
  size_t within = 0;
  for (int y = 0; y < value.height; ++y)
    for (int x = 0; x < value.width; ++x) {
      const double e = double(texel_luminance(value, x, y)) - texel_luminance(reference, x, y);
      const double a = value_stderr.at(x, y, 0), b = reference_stderr.at(x, y, 0);
      const double sigma = std::sqrt(a * a + b * b);
      if (!(sigma > 0.0) || !std::isfinite(e)) continue;
      ratios.push_back(std::abs(e) / sigma);
      if (std::abs(e) <= 2.0 * sigma) ++within;
    }
  ProbeCalibration c;
  c.texels = ratios.size();
  if (ratios.empty()) {
    c.median_ratio = c.within_two_sigma = std::numeric_limits<double>::quiet_NaN();
    return c;
  }
  std::nth_element(ratios.begin(), ratios.begin() + ptrdiff_t(ratios.size() / 2), ratios.end());
  c.median_ratio = ratios[ratios.size() / 2] / kGaussianMedianAbs;
  c.within_two_sigma = double(within) / double(ratios.size());
  return c;
}

}  // namespace phyir::render
