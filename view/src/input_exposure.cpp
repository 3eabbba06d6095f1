#include "phyir/view/input_exposure.h"

#include <cmath>

#include "phyir/core/error.h"
#include "phyir/view/view_files.h"

namespace phyir::view {

double InputExposure::factor() const { return std::exp2(stops); }

nlohmann::json InputExposure::to_json() const {
  nlohmann::json j = {{"file", kInputFile},        {kExposureStopsKey, stops}, {"base_stops", base_stops},
                      {"jitter_stops", jitter_stops}, {"display", "sRGB"},        {"view", view}};
  if (percentile_value) j["percentile_value"] = *percentile_value;
  return j;
}

InputExposure InputExposure::from_json(const nlohmann::json& input, const std::string& source) {
  InputExposure e;
  if (!input.is_object() || !input.contains(kExposureStopsKey)) return e;
  const auto number = [&](const char* key) {
    const nlohmann::json& v = input.at(key);
    if (!v.is_number()) fail("{}: input.{} is {}, not a number", source, key, v.dump());
    return v.get<double>();
  };
  e.stops = number(kExposureStopsKey);
  if (input.contains("base_stops")) e.base_stops = number("base_stops");
  if (input.contains("jitter_stops")) e.jitter_stops = number("jitter_stops");
  if (input.contains("percentile_value")) e.percentile_value = number("percentile_value");
  e.view = input.value("view", std::string("Standard"));
  e.recorded = true;
  return e;
}

}  // namespace phyir::view
