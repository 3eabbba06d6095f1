#include "phyir/dataset/settings.h"

#include <cmath>
#include <string>

#include <fmt/format.h>

#include "phyir/core/colour.h"
#include "phyir/core/setting_error.h"
#include "phyir/dataset/checksum.h"
#include "phyir/view/input_exposure.h"
#include "phyir/view/view_files.h"

namespace phyir::dataset {

nlohmann::json ViewpointRules::to_json() const {
  return {{"min_height_m", min_height}, {"max_height_m", max_height},   {"clearance_m", clearance},
          {"clearance_rays", clearance_rays}, {"min_spacing_m", min_spacing}, {"attempts", attempts}};
}

void DatasetSettings::validate() const {
  if (width <= 0 || height <= 0 || width > 65536 || height > 65536)
    fail_setting("size", "{}x{} must be between 1 and 65536", width, height);
  if (width != 2 * height)
    fail_setting("size", "{}x{}: the width must be twice the height: views are 360x180 degree panoramas", width,
                 height);
  if (spp <= 0) fail_setting("spp", "{} must be positive", spp);
  if (max_bounces < 0) fail_setting("max_bounces", "{} must be >= 0", max_bounces);
  if (probes) probe.validate();
  if (!std::isfinite(preview_exposure)) fail_setting("preview_exposure", "must be finite");
  if (!std::isfinite(input.exposure_stops))
    fail_setting("input.exposure_stops", "must be 'auto' or a finite number of stops");
  if (!(input.percentile > 0.0 && input.percentile <= 1.0))
    fail_setting("input.percentile", "{} must be in (0, 1]", input.percentile);
  if (!(input.target > 0.0) || !std::isfinite(input.target))
    fail_setting("input.target", "{} must be positive", input.target);
  if (!(input.jitter_stops >= 0.0f) || !std::isfinite(input.jitter_stops))
    fail_setting("input.jitter_stops", "{} must be a finite number of stops >= 0", input.jitter_stops);
  if (input.view != "Standard" && input.view != "Raw")
    fail_setting("input.view", "'{}' must be Standard or Raw", input.view);
  const ViewpointRules& v = viewpoints;
  if (!(v.min_height >= 0.0f && v.max_height >= v.min_height))
    fail_setting("viewpoints.min_height", "heights {}-{} m must satisfy 0 <= min <= max", v.min_height, v.max_height);
  if (!(v.clearance >= 0.0f)) fail_setting("viewpoints.clearance", "{} must be >= 0 metres", v.clearance);
  if (v.clearance_rays < 6) fail_setting("viewpoints.clearance_rays", "{} must be at least 6", v.clearance_rays);
  if (!(v.min_spacing >= 0.0f)) fail_setting("viewpoints.min_spacing", "{} must be >= 0 metres", v.min_spacing);
  if (v.attempts < 1) fail_setting("viewpoints.attempts", "{} must be at least 1", v.attempts);
  if (views_per_scene < 1 || views_per_scene > 9999)
    fail_setting("views_per_scene", "{} must be between 1 and 9999", views_per_scene);
  if (seed > (uint64_t(1) << 53)) fail_setting("seed", "{} must be at most 2^53 (it is stored in JSON)", seed);
  const double sum = split.train + split.val + split.test;
  if (split.train < 0 || split.val < 0 || split.test < 0 || std::abs(sum - 1.0) > 1e-6)
    fail_setting("split", "{},{},{} must be three fractions >= 0 that sum to 1", split.train, split.val, split.test);
}

nlohmann::json DatasetSettings::to_json() const {
  nlohmann::json probe_json = nullptr;
  if (probes) {
    probe_json = probe.to_json();
    // The view's seed and path settings are used for probes (RenderJob): do not record the
    // unused copies.
    probe_json.erase("seed");
    probe_json.erase("max_bounces");
  }
  nlohmann::json input_json = {{"file", view::kInputFile},
                               {"exposure", input.auto_exposure ? "auto" : "fixed"},
                               {"jitter_stops", input.jitter_stops},
                               {"display", "sRGB"},
                               {"view", input.view},
                               {"ocio_config_sha256", ocio_config_sha256()}};
  if (input.auto_exposure) {
    input_json["percentile"] = input.percentile;
    input_json["target"] = input.target;
  } else {
    input_json[view::kExposureStopsKey] = input.exposure_stops;
  }
  return tidy_floats({{"preset", preset},
          {"render", {{"projection", "equirect"},
                      {"width", width},
                      {"height", height},
                      {"spp", spp},
                      {"max_bounces", max_bounces},
                      {"roulette_start", render::PathSettings{}.roulette_start},
                      {"aovs", true},
                      {"preview_exposure_stops", preview_exposure},
                      {"preview_view", "Standard"}}},
          {"probes", probe_json},
          {"input", input_json},
          {"viewpoints", viewpoints.to_json()},
          {"views_per_scene", views_per_scene},
          {"seed", seed},
          {"split", {{"train", split.train}, {"val", split.val}, {"test", split.test}}}});
}

const std::vector<std::string>& preset_names() {
  static const std::vector<std::string> names = {"tiny", "cpu", "paper"};
  return names;
}

DatasetSettings preset_settings(const std::string& name) {
  DatasetSettings s;
  s.preset = name;
  render::ProbeLayout& layout = s.probe.layout;
  if (name == "tiny") {
    // Seconds per view: for tests and smoke runs, not for training.
    s.width = 64;
    s.height = 32;
    s.spp = 4;
    s.max_bounces = 4;
    layout = {8, 16, 4, 8};
    s.probe.spp = 2;
    s.probe.cache.samples_per_cell = 16;
  } else if (name == "cpu") {
    // The default: a useful training resolution at a cost a CPU node sustains
    // (docs/dataset.md has the measured views per hour).
    s.width = 512;
    s.height = 256;
    s.spp = 64;
    s.max_bounces = 8;
    layout = {64, 128, 8, 16};
    s.probe.spp = 4;
  } else if (name == "paper") {
    // The paper's sizes (sec. 3.1 and C.1): a 256x512 panorama, a 128x256 grid of 16x32
    // probes (one per 2x2 pixel block).
    s.width = 512;
    s.height = 256;
    s.spp = 256;
    s.max_bounces = 8;
    layout = {128, 256, 16, 32};
    s.probe.spp = 8;
  } else {
    fail_setting("preset", "'{}' is unknown; use tiny, cpu or paper", name);
  }
  return s;
}

nlohmann::json tidy_floats(nlohmann::json value) {
  if (value.is_number_float()) {
    const double d = value.get<double>();
    const float f = static_cast<float>(d);
    if (std::isfinite(d) && static_cast<double>(f) == d) return std::stod(fmt::format("{}", f));
    return value;
  }
  if (value.is_structured())
    for (auto& item : value) item = tidy_floats(std::move(item));
  return value;
}

std::string ocio_config_sha256() {
  static const std::string digest = sha256_file(ocio_config_path());
  return digest;
}

}  // namespace phyir::dataset
