#pragma once
// What a user sets to render a view's light probes (docs/probes.md, "Knobs"): the layout,
// the mode, the sample counts and the radiance cache's and the sharing's settings. Every
// default is written once, here.
#include <cstdint>
#include <string>

#include <nlohmann/json.hpp>

#include "phyir/render/path_tracer.h"
#include "phyir/render/probe_grid.h"

namespace phyir::render {

// The radiance cache of cache mode (docs/probes-estimator.md, "The radiance cache").
struct RadianceCacheSettings {
  float cell_size = 0.05f;    // metres
  int samples_per_cell = 128;  // irradiance estimates per cell
  // Direct light is cached in cells at least this many cell sizes from every emitter
  // (0: never). Linear interpolation's error is about 0.75 (cell / distance)^2 of the
  // irradiance under a point light: 2% at 6 cells.
  float direct_distance_cells = 6.0f;
  // Lookups read each cell's indirect light as the mean over its 3 x 3 x 3 neighbourhood in
  // its normal bucket (docs/probes-estimator.md, "The radiance cache").
  bool smooth_indirect = true;
  uint64_t seed = 0;
  bool progress = false;
};

// Texels averaged with the same texel of neighbouring probes on one surface
// (docs/probes-estimator.md, "Sharing between neighbours").
struct ProbeSharing {
  int radius = 1;                // window (2r+1)^2; 0: no sharing
  float parallax_texels = 0.5f;  // largest accepted parallax, in texel extents
  float max_baseline = 0.25f;    // metres

  int window() const { return 2 * radius + 1; }
};

enum class ProbeMode { kPath, kCache };

ProbeMode parse_probe_mode(const std::string& name);  // "path" | "cache"; else SettingError "probe.mode"
std::string probe_mode_name(ProbeMode mode);

struct ProbeSettings {
  ProbeLayout layout;
  int spp = 4;                    // directions per texel (docs/probes.md: the measured default)
  ProbeMode mode = ProbeMode::kCache;
  float offset = 0.01f;           // metres off the surface, along its shading normal
  uint64_t seed = 0;
  PathSettings path;              // max_bounces counts scattering after the probe ray's hit
  // kCache only.
  RadianceCacheSettings cache;    // its seed and progress are derived from this struct's
  int hard_spp_factor = 6;        // hard texels (lights, glass, glossy, edges) get this many times spp
  // A texel whose first spp samples' luminances spread over more than this times their
  // mean (plus a small floor) is hard: an edge, a highlight or a shadow boundary in it.
  float spread_threshold = 0.75f;
  // Extra directions for a probe's noisiest texels, as a fraction of those its texels took:
  // shared out in proportion to each texel's noise per direction (docs/probes-estimator.md,
  // "Balancing the texels' noise"); 0: none.
  float balance = 1.0f;
  float glossy_roughness = 0.3f;  // secondary hits smoother than this are traced on
  // The probability that a specular chain's end is path traced instead of ending in the cache
  // as a uniformly lit lobe (docs/probes-estimator.md, "The texel estimator", 5). Set by the passes'
  // schedule (probe_pass_schedule.h): 0 in the first pass.
  float chain_end_paths = 0.0f;
  ProbeSharing sharing;           // texels averaged with neighbouring probes' (docs/probes-estimator.md, "Sharing between neighbours")
  bool correct_foot = true;       // the cache's error at each probe's foot taken out (docs/probes-estimator.md, "The foot correction")
  // Photons from each point and spot light, and per square metre of the sun's beam where it
  // reaches the probes, take the light they reflect at the first hits where they land densely
  // (docs/probes-estimator.md, "Photons round punctual lights and the sun"); 0: none.
  int photons_per_light = 4096;
  // Punctual lights added, exactly, to the texel each one's direction falls in (docs/probes.md,
  // "What a texel is"). Both modes; off only to measure the estimated part alone.
  bool punctual_lights = true;
  // Render again where the noise is until the grid's estimated relative error (from each
  // texel's standard error) is at most this (docs/probes.md, "Accuracy as a target"); 0: one pass.
  float target_error = 0.0f;
  // Passes after the first shrink cache mode's reuse kernels (cells, sharing's parallax
  // bound) as (k + 1)^(-1/3), so that their mean is consistent (docs/probes.md, "Accuracy as
  // a target"); false: every pass as the first, with its own seed.
  bool progressive = true;
  bool progress = true;

  // Throws phyir::SettingError naming the setting ("probe.spp", "probe.cache.cell_size", ...)
  // and the value.
  void validate() const;
  nlohmann::json to_json() const;
};

}  // namespace phyir::render
