#pragma once
// What a user sets to render a view's light probes (docs/probes.md, "Knobs"). Every default
// is written once, here.
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
  // Direct light cached in cells at least this many cell sizes from every emitter (0: never):
  // interpolation's error under a point light, ~0.75 (cell / distance)^2, is 2% at 6.
  float direct_distance_cells = 6.0f;
  // Lookups read each cell's indirect light as its 3 x 3 x 3 neighbourhood's mean.
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
  // Hard texels (lights, glass, glossy, edges) get this many times spp; at least 16 x where
  // they saw the sky (docs/probes-estimator.md, "Hard texels").
  int hard_spp_factor = 6;
  // A texel whose first spp luminances spread over more than this x (their mean + a floor)
  // is hard: an edge, a highlight or a shadow boundary.
  float spread_threshold = 0.75f;
  // Extra directions for a probe's noisiest texels, as a fraction of those its texels took,
  // by noise per direction (docs/probes-estimator.md, "Balancing the texels' noise"); 0: none.
  float balance = 1.0f;
  float glossy_roughness = 0.3f;  // secondary hits smoother than this are traced on
  // Probability a glossy chain's end is path traced, not a uniformly lit lobe from the cache
  // (docs/probes.md, "Accuracy as a target"); set by probe_pass_schedule.h, 0 in the first pass.
  float chain_end_paths = 0.0f;
  ProbeSharing sharing;           // texels averaged with neighbouring probes' (docs/probes-estimator.md, "Sharing between neighbours")
  bool correct_foot = true;       // the cache's error at each probe's foot taken out (docs/probes-estimator.md, "The foot correction")
  // Photons per point or spot light and per m^2 of the sun's beam where it reaches the probes,
  // taking the light they reflect where they land densely; 0: none (docs/probes-estimator.md,
  // "Photons round punctual lights and the sun").
  int photons_per_light = 4096;
  // Punctual lights added exactly to the texel of their direction, both modes (docs/probes.md,
  // "What a texel is"); off only to measure the estimated part alone.
  bool punctual_lights = true;
  // Render again until the grid's estimated relative error is at most this (docs/probes.md,
  // "Accuracy as a target"); 0: one pass.
  float target_error = 0.0f;
  // Later passes shrink cache mode's kernels as (k + 1)^(-1/3), so their mean is consistent
  // (docs/probes.md, "Accuracy as a target"); false: every pass as the first, own seed.
  bool progressive = true;
  bool progress = true;

  // Throws phyir::SettingError naming the setting ("probe.spp", ...) and the value.
  void validate() const;
  nlohmann::json to_json() const;
};

}  // namespace phyir::render
