#pragma once
// The exposure of a view's input image (docs/conventions.md "Input exposure"). input.png is
// sRGB(clip(2^stops x color.exr)) through OpenColorIO's display view ("Standard": the sRGB
// curve; "Raw": none), `stops` chosen per view (auto exposure plus an optional jitter) and
// recorded in view.json's "input" block. Readers that find no record take 0 stops.
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

namespace phyir::view {

// The key of a stops value in every record (view.json input, render.json color_png, settings).
inline constexpr const char* kExposureStopsKey = "exposure_stops";

struct InputExposure {
  double stops = 0.0;                      // what input.png used: base + jitter
  double base_stops = 0.0;                 // auto exposure, or the fixed value
  double jitter_stops = 0.0;               // this view's draw in [-jitter, +jitter]
  std::optional<double> percentile_value;  // auto exposure: the percentile of color.exr's RGB values
  std::string view = "Standard";           // the OpenColorIO view: Standard or Raw
  bool recorded = false;                   // read from a record (false: none, 0 stops assumed)

  double factor() const;                   // 2^stops
  bool raw_view() const { return view == "Raw"; }

  // view.json's "input" block.
  nlohmann::json to_json() const;
  // From a record's "input" block (`input` may be null: not recorded). A non-numeric
  // exposure: phyir::Error naming `source`.
  static InputExposure from_json(const nlohmann::json& input, const std::string& source);
};

}  // namespace phyir::view
