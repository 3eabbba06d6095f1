#pragma once
// Renders the per-pixel light probes of one view (settings: probe_settings.h; placement:
// probe_grid.h; docs/probes.md): each texel from `spp` stratified directions, by the path tracer
// (ProbeMode::kPath, the unbiased reference) or over a radiance cache the view's probes share
// (ProbeMode::kCache; docs/probes-estimator.md). Streams are keyed by (seed, probe, texel,
// sample), the cache's by (seed, cell, sample): probes.exr is bit-identical for a seed whatever
// the thread count. Non-finite samples are counted and zeroed.
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "phyir/core/image.h"
#include "phyir/render/effects.h"
#include "phyir/render/camera.h"
#include "phyir/render/path_counters.h"
#include "phyir/render/probe_grid.h"
#include "phyir/render/probe_settings.h"
#include "phyir/render/render_scene.h"
#include "phyir/view/probe_mosaic.h"

namespace phyir::render {

// The grid's estimated error and, with a target (ProbeSettings::target_error), the passes
// made to reach it (docs/probes.md, "Accuracy as a target").
struct ProbeErrorTarget {
  double target = 0.0;     // 0: none
  double estimated = 0.0;  // sqrt(mean sigma^2) / mean luminance over the valid probes' texels, x sigma_factor
  double sigma_factor = 1.0;  // how far independent passes' differences put sigma off (1: one pass)
  int passes = 1;          // of the probes refined most
  uint64_t refined_probes = 0;  // probes rendered again, summed over the passes
  nlohmann::json to_json() const;
};

struct ProbeStats {
  double place_seconds = 0.0;
  double cache_seconds = 0.0;  // discovery + fill
  double shade_seconds = 0.0;
  double total_seconds = 0.0;
  PathCounters counters;          // every ray of the probes (placement excluded)
  uint64_t placement_rays = 0;
  uint64_t probes = 0, valid = 0, nothing = 0, emitter = 0, transparent = 0;
  uint64_t computed_probes = 0;   // probes actually rendered (all but kNothing, or a subset)
  uint64_t supersampled_texels = 0;
  uint64_t balanced_texels = 0;  // texels given a probe's extra directions by their noise (probe.balance)
  uint64_t deep_texels = 0;  // hard texels whose hard samples still held a rare bright part: sampled again, deeper
  uint64_t shared_texels = 0;     // texels averaged with at least one neighbour's
  uint64_t light_texels = 0;      // texels a light may cover (emission estimated apart)
  uint64_t light_edge_texels = 0; // of those, texels a light's outline crosses (16x the emission directions)
  uint64_t emission_rays = 0;     // rays of those texels' emission seen directly (in counters.rays)
  uint64_t cache_rays = 0;        // rays of the cache's discovery and fill (in counters.rays)
  uint64_t photons = 0;           // the punctual lights' photons (punctual_photons.h)
  uint64_t photon_rays = 0;       // their rays and the probes' shadow rays to them (in counters.rays)
  uint64_t photon_texels = 0;     // texels the photons added light to
  uint64_t negative_texels = 0;   // texel estimates below zero (the control variate's), clamped to 0
  uint64_t foot_corrections = 0;  // probes whose own-surface texels took the cache's error out (foot_correction.h)
  glm::vec3 foot_common_difference{0.0f};  // the difference common to all probes (the last bounce), W/m^2
  double share_seconds = 0.0;
  ProbeErrorTarget error;
  uint64_t cache_cells = 0, cache_direct_cells = 0, cache_fill_samples = 0, cache_fallbacks = 0;
  // Adds the counts of `o` (its seconds and cache figures are left out: they are the view's).
  ProbeStats& operator+=(const ProbeStats& o);
  uint64_t rays() const { return counters.rays + placement_rays; }
  nlohmann::json to_json() const;     // render.json's probe statistics
  nlohmann::json counts_json() const;  // its "counts": valid and invalid probes by cause
  nlohmann::json cache_json() const;   // its "cache": cells, fill samples, fallbacks
};

// A texel's supersampling choice in one render (docs/probes-estimator.md, "Hard texels").
enum TexelChoice : uint8_t { kPlainTexel = 0, kHardTexel = 1, kDeepTexel = 2 };

struct ProbeOutput {
  ProbeLayout layout;
  std::vector<ProbeSite> sites;  // row-major, H x W
  Image mosaic;                  // (H h) x (W w) RGB radiance
  // (H h) x (W w), Y: each texel's standard error in luminance, its own samples' variance
  // pooled with its neighbours'; without the noise of the shared cache, of the light estimated
  // apart and of the photons (docs/probes.md, "Per-texel standard error").
  Image standard_error;
  Image position;                // H x W, X,Y,Z: probe origins (0 where nothing is seen)
  Image normal;                  // H x W, X,Y,Z: the normal each origin is offset along
  Image mask;                    // H x W, Y: 1 for valid probes
  ProbeStats stats;
  // With an error target: each texel's TexelChoice in this render as its own samples made it
  // (probe x texels + texel); a later pass also supersamples what an earlier one chose.
  std::vector<uint8_t> texel_choices;
  // With an error target: the directions behind each texel's value, its weight when passes
  // are merged (probe_error_target.h).
  std::vector<float> texel_samples;
};

class ProbeRenderer {
 public:
  // Throws phyir::SettingError naming the setting for invalid settings. Keeps a reference to the
  // scene, which must outlive it.
  ProbeRenderer(const RenderScene& scene, const Effects& effects, const ProbeSettings& settings);

  // Places and renders every probe of the view.
  ProbeOutput render(const CameraModel& camera) const;

  // Renders probes at given sites (row-major for settings.layout). A non-empty `subset`
  // renders only those indices (the others stay 0), as a full render would in kPath (kCache
  // builds its cache from the subset alone). With an error target, renders again until met.
  ProbeOutput render_at(std::vector<ProbeSite> sites, const std::vector<int>& subset = {}) const;

 private:
  const RenderScene& scene_;
  Effects effects_;
  ProbeSettings settings_;
};

// ProbeRenderer(scene, effects, settings).render(camera).
ProbeOutput render_probes(const RenderScene& scene, const CameraModel& camera, const Effects& effects,
                          const ProbeSettings& settings);

// The h x w probe (i, j) cut out of a mosaic: the view module's.
using view::probe_image;

}  // namespace phyir::render
