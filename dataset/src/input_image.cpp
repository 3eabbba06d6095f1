#include "phyir/dataset/input_image.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <fmt/format.h>

#include "phyir/core/colour.h"
#include "phyir/core/image_io.h"
#include "phyir/dataset/checksum.h"

namespace phyir::dataset {

namespace {
// A black or nearly black view would otherwise ask for an absurd gain.
constexpr float kMaxAutoStops = 32.0f;
}  // namespace

nlohmann::json InputExposure::to_json(const InputSettings& settings) const {
  nlohmann::json j = {{"file", "input.png"},
                      {"exposure_stops", stops},
                      {"base_stops", base_stops},
                      {"jitter_stops", jitter_stops},
                      {"display", "sRGB"},
                      {"view", settings.view}};
  if (settings.auto_exposure) j["percentile_value"] = percentile_value;
  return j;
}

InputExposure choose_input_exposure(const Image& color, const InputSettings& settings, uint64_t view_seed) {
  InputExposure e;
  if (settings.auto_exposure) {
    std::vector<float> values;
    const int channels = std::min(color.channels, 3);
    values.reserve(size_t(color.width) * color.height * channels);
    for (size_t p = 0; p + color.channels <= color.pixels.size(); p += color.channels)
      for (int c = 0; c < channels; ++c) values.push_back(color.pixels[p + c]);
    if (!values.empty()) {
      const size_t k = std::min(values.size() - 1, static_cast<size_t>(settings.percentile * double(values.size())));
      std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(k), values.end());
      e.percentile_value = values[k];
    }
    if (e.percentile_value > 0.0f && std::isfinite(e.percentile_value))
      e.base_stops = std::clamp(float(std::log2(settings.target / double(e.percentile_value))), -kMaxAutoStops,
                                kMaxAutoStops);
  } else {
    e.base_stops = settings.exposure_stops;
  }
  if (settings.jitter_stops > 0.0f) {
    const double u = hash_unit(fmt::format("phyir-dataset exposure|{}", view_seed));
    e.jitter_stops = float(double(settings.jitter_stops) * (2.0 * u - 1.0));
  }
  e.stops = e.base_stops + e.jitter_stops;
  return e;
}

void write_input_image(const std::filesystem::path& path, const Image& color, const InputExposure& exposure,
                       const InputSettings& settings) {
  write_image(path, linear_to_display(color, exposure.stops, settings.view));
}

}  // namespace phyir::dataset
