#include "phyir/core/auto_exposure.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace phyir {

AutoExposure auto_exposure(const Image& linear, double percentile, double target) {
  AutoExposure e;
  const int channels = std::min(linear.channels, 3);
  std::vector<float> values;
  values.reserve(size_t(linear.width) * linear.height * channels);
  for (size_t p = 0; p + linear.channels <= linear.pixels.size(); p += linear.channels)
    for (int c = 0; c < channels; ++c) values.push_back(linear.pixels[p + c]);
  if (values.empty()) return e;
  const size_t k = std::min(values.size() - 1, static_cast<size_t>(percentile * double(values.size())));
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(k), values.end());
  e.percentile_value = values[k];
  if (e.percentile_value > 0.0f && std::isfinite(e.percentile_value))
    e.stops = std::clamp(float(std::log2(target / double(e.percentile_value))), -kMaxAutoExposureStops,
                         kMaxAutoExposureStops);
  return e;
}

}  // namespace phyir
