#include "phyir/dataset/input_image.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <fmt/format.h>

#include "phyir/core/auto_exposure.h"
#include "phyir/core/colour.h"
#include "phyir/core/image_io.h"
#include "phyir/dataset/checksum.h"

namespace phyir::dataset {

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
    const AutoExposure a = auto_exposure(color, settings.percentile, settings.target);
    e.percentile_value = a.percentile_value;
    e.base_stops = a.stops;
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
