#pragma once
// Everything that decides a dataset's bytes, as one value: render settings, probes, the
// network input's exposure, viewpoint rules, views per scene, split fractions and the seed.
// Presets (tiny, cpu, paper) are named bundles of these; a command may then set single fields.
// The JSON form (to_json) is what settings.json and manifest.json record, and what a
// re-run and `dataset merge` compare: two runs with equal JSON write equal files.
// Thread counts and paths are not settings: they never change a byte.
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "phyir/render/probe_renderer.h"

namespace phyir::dataset {

// input.png, the network's LDR input: HDR color through OpenColorIO (core/colour.h) with
// an exposure in stops, then the sRGB display and `view`.
//  - auto: the exposure maps the `percentile` of all RGB values of color.exr to `target`
//    (the loader of Li et al. / the PhyIR training code does the same with the 95th
//    percentile and a target drawn in [0.85, 0.95]); a black image gets 0 stops.
//  - fixed: `exposure_stops` for every view.
// Then a per-view jitter uniform in [-jitter_stops, +jitter_stops], drawn from the view's
// seed, is added (random exposure, recorded per view).
struct InputSettings {
  bool auto_exposure = true;
  float exposure_stops = 0.0f;  // fixed mode
  double percentile = 0.95;     // auto mode
  double target = 0.9;          // auto mode
  float jitter_stops = 0.0f;
  std::string view = "Standard";  // OCIO view of the sRGB display: Standard or Raw
};

// Where views come from after the scene's own cameras and candidates (viewpoints.h).
struct ViewpointRules {
  float min_height = 1.2f;   // metres above the floor (the scene's lowest point)
  float max_height = 1.8f;
  float clearance = 0.3f;    // metres from every surface, measured by rays
  int clearance_rays = 256;  // directions on a Fibonacci sphere: ~7 cm apart at 0.3 m
  float min_spacing = 0.5f;  // metres between a sampled viewpoint and every other one
  int attempts = 4000;       // candidate points drawn per missing viewpoint before giving up

  nlohmann::json to_json() const;
};

// Fractions of scenes (not views) per split; they must sum to 1.
struct SplitFractions {
  double train = 0.8;
  double val = 0.1;
  double test = 0.1;
};

struct DatasetSettings {
  std::string preset = "cpu";  // the bundle this started from (single fields may differ)
  int width = 512;             // equirectangular panorama, width = 2 height
  int height = 256;
  int spp = 64;
  int max_bounces = 8;
  bool probes = true;
  render::ProbeSettings probe;  // layout, spp, mode, cache parameters (seed/path: the view's)
  float preview_exposure = 0.0f;  // color.png (the render's own preview): fixed stops, Standard view
  InputSettings input;
  ViewpointRules viewpoints;
  int views_per_scene = 8;
  uint64_t seed = 1;
  SplitFractions split;

  // Throws phyir::SettingError naming the setting ("size", "spp", "probe.grid", "input.target",
  // "viewpoints.clearance", ...) and the value.
  void validate() const;
  nlohmann::json to_json() const;
};

// tiny (tests: 64x32, 4 spp, 8x16 probes of 4x8 texels), cpu (the default: 512x256,
// 64 spp, 64x128 probes of 8x16), paper (the paper's 256x512 panorama with a 128x256 grid of
// 16x32 probes). Throws phyir::SettingError ("preset") listing the names for an unknown one.
DatasetSettings preset_settings(const std::string& name);
const std::vector<std::string>& preset_names();

// Every number of `value` that is a float widened to double (0.949999988079071) replaced by
// the double of the float's shortest decimal form (0.95), so JSON records read as written.
// Deterministic and idempotent.
nlohmann::json tidy_floats(nlohmann::json value);

// The OCIO config's SHA-256 (recorded: input.png depends on it).
std::string ocio_config_sha256();

}  // namespace phyir::dataset
