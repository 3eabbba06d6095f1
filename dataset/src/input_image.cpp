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

InputExposure choose_input_exposure(const Image& color, const InputSettings& settings, uint64_t view_seed) {
  // Stops are computed in float (the record's precision since the first datasets) and stored.
  float base = settings.exposure_stops, jitter = 0.0f;
  InputExposure e;
  if (settings.auto_exposure) {
    const AutoExposure a = auto_exposure(color, settings.percentile, settings.target);
    e.percentile_value = a.percentile_value;
    base = a.stops;
  }
  if (settings.jitter_stops > 0.0f) {
    const double u = hash_unit(fmt::format("phyir-dataset exposure|{}", view_seed));
    jitter = float(double(settings.jitter_stops) * (2.0 * u - 1.0));
  }
  e.base_stops = base;
  e.jitter_stops = jitter;
  e.stops = base + jitter;
  e.view = settings.view;
  e.recorded = true;
  return e;
}

void write_input_image(const std::filesystem::path& path, const Image& color, const InputExposure& exposure,
                       const InputSettings& settings) {
  write_image(path, linear_to_display(color, float(exposure.stops), settings.view));
}

}  // namespace phyir::dataset
