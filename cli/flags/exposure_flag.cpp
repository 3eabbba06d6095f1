#include "exposure_flag.h"

#include <cmath>
#include <sstream>

#include <fmt/format.h>

#include "flag_registry.h"
#include "phyir/core/error.h"

namespace phyir::cli {

namespace {
constexpr const char* kGroup = "Exposure";
}  // namespace

std::optional<float> parse_exposure_flag(const std::string& text, const char* flag) {
  if (text == "auto") return std::nullopt;
  std::istringstream in(text);
  float stops = 0.0f;
  if (!(in >> stops) || !in.eof() || !std::isfinite(stops))
    fail("{} '{}' must be 'auto' or a finite number of stops", flag, text);
  return stops;
}

CLI::Option* add_exposure_flag(CLI::App* cmd, bool& auto_exposure, float& stops, const std::string& image,
                               const std::string& setting) {
  // The auto rule's figures as the dataset's input.png uses them by default; `phyir render`'s
  // color.png follows the same rule.
  const dataset::InputSettings rule;
  const std::string help =
      fmt::format("{}'s exposure: auto (the {:g}th percentile of the HDR image's values maps to {:g}{}) or a number of "
                  "stops",
                  image, 100.0 * rule.percentile, rule.target, image == "input.png" ? "" : ", as for the dataset's input.png");
  return sets(cmd, setting,
              cmd->add_option_function<std::string>(
                  "--exposure",
                  [&auto_exposure, &stops](const std::string& text) {
                    const std::optional<float> given = parse_exposure_flag(text);
                    auto_exposure = !given;
                    if (given) stops = *given;
                  },
                  help))
      ->default_str(auto_exposure ? "auto" : fmt::format("{:g}", stops))
      ->group(kGroup);
}

CLI::Option* add_view_flag(CLI::App* cmd, std::string& view, const std::string& image, const std::string& setting) {
  return sets(cmd, setting, cmd->add_option("--view", view, "OpenColorIO view of " + image + ": Standard or Raw"))
      ->capture_default_str()
      ->group(kGroup);
}

void add_input_exposure_flags(CLI::App* cmd, dataset::InputSettings& input) {
  add_exposure_flag(cmd, input.auto_exposure, input.exposure_stops, "input.png", "input.exposure_stops");
  sets(cmd, "input.percentile",
       cmd->add_option("--exposure-percentile", input.percentile, "auto exposure: the percentile of the HDR values used"))
      ->capture_default_str()
      ->group(kGroup);
  sets(cmd, "input.target",
       cmd->add_option("--exposure-target", input.target, "auto exposure: the value that percentile maps to"))
      ->capture_default_str()
      ->group(kGroup);
  sets(cmd, "input.jitter_stops",
       cmd->add_option("--exposure-jitter", input.jitter_stops,
                       "random exposure: add a per-view draw in [-J, +J] stops (recorded)"))
      ->capture_default_str()
      ->group(kGroup);
  add_view_flag(cmd, input.view, "input.png", "input.view");
}

}  // namespace phyir::cli
