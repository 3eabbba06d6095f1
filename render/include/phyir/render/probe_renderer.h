#pragma once
// Renders the per-pixel light probes of one view (layout and placement: probe_grid.h;
// user documentation, the modes and the measured cost of each: docs/probes.md).
//
// Each texel is the incident radiance at the probe's origin averaged over the texel's solid
// angle: `spp` directions per texel, stratified and uniform in solid angle inside it
// (probe_texel_direction), each one's radiance estimated by
//  - ProbeMode::kPath: the path tracer, exactly as a camera ray of color.exr (unbiased; the
//    reference the other mode is measured against);
//  - ProbeMode::kCache: the direction's first hit x is found by one ray; its emission is
//    added exactly. Where the view's RadianceCache holds x's direct irradiance too (far
//    from the emitters), the diffuse part of all light at x is f_d(x) E(x) and the specular
//    part is sampled apart (next-event estimation and a GGX-sampled ray through f_s,
//    Russian-rouletted by its share of the albedo). Elsewhere direct light at x is sampled
//    as the integrator does (next-event estimation, with 8 light samples at x, plus one
//    BRDF-sampled ray, power-heuristic MIS); indirect diffuse light is f_d(x) E(x) with E's indirect part;
//    indirect specular light comes through the BRDF-sampled ray: the specular part of its weight
//    times the light its hit y reflects, followed recursively for glossy y seen from a
//    glossy x (roughness below glossy_roughness, up to kMaxSpecularDepth) and otherwise
//    next-event estimation at y
//    plus (f_d(y) + specular albedo(y)/pi) E(y); on rough dielectrics that evaluation is
//    Russian-rouletted by the specular share of the weight, with the lobe under uniform light
//    of E's mean radiance as a control variate. Glass at x is path traced.
//    Afterwards each texel is averaged with the same texel of neighbouring probes on the
//    same surface where its content is far enough for the parallax to be small
//    (probe_sharing.h).
//    "Hard" texels are re-estimated from hard_spp_factor x spp fresh directions: those the
//    scene's emissive triangles can cover (projected onto the probe before sampling; their
//    directly seen emission is estimated apart, from directions drawn inside the lights'
//    exact coverage of the texel, EmitterCoverage, that only ask whether an occluder hides
//    the light) and those whose first spp directions met a light, glass or a glossy surface.
// Random numbers: sample s of texel t of probe p draws from streams keyed by
// (seed, p, t, s) (streams.h), the cache's from (seed, cell,
// sample); so probes.exr is bit-identical for a seed whatever the thread count. Non-finite
// samples are counted and zeroed.
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "phyir/core/image.h"
#include "phyir/render/effects.h"
#include "phyir/render/path_tracer.h"
#include "phyir/render/probe_grid.h"
#include "phyir/render/probe_sharing.h"
#include "phyir/render/render_scene.h"

namespace phyir::render {

enum class ProbeMode { kPath, kCache };

ProbeMode parse_probe_mode(const std::string& name);  // "path" | "cache"
std::string probe_mode_name(ProbeMode mode);

struct ProbeSettings {
  ProbeLayout layout;
  int spp = 4;                    // directions per texel (docs/probes.md: the measured default)
  ProbeMode mode = ProbeMode::kCache;
  float offset = 0.01f;           // metres off the surface, along its shading normal
  uint64_t seed = 0;
  PathSettings path;              // max_bounces counts scattering after the probe ray's hit
  // kCache only.
  float cache_cell = 0.05f;       // metres
  int cache_spp = 128;            // irradiance estimates per cache cell
  float cache_direct_cells = 6.0f;  // direct light cached this many cells from emitters (0: never)
  int hard_spp_factor = 6;        // hard texels (lights, glass, glossy, edges) get this many times spp
  // A texel whose first spp samples' luminances spread over more than this times their
  // mean (plus a small floor) is hard: an edge, a highlight or a shadow boundary in it.
  float spread_threshold = 0.75f;
  float glossy_roughness = 0.3f;  // secondary hits smoother than this are traced on
  ProbeSharing sharing;           // texels averaged with neighbouring probes' (probe_sharing.h)
  bool correct_foot = true;       // the cache's error at each probe's foot taken out (foot_correction.h)
  bool progress = true;

  void validate() const;  // throws phyir::Error naming the flag
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
  uint64_t shared_texels = 0;     // texels averaged with at least one neighbour's
  uint64_t light_texels = 0;      // texels a light may cover (emission estimated apart)
  uint64_t light_edge_texels = 0; // of those, texels a light's outline crosses (16x the emission directions)
  uint64_t negative_texels = 0;   // texel estimates below zero (the control variate's), clamped to 0
  uint64_t foot_corrections = 0;  // probes whose own-surface texels took the cache's error out (foot_correction.h)
  glm::vec3 foot_common_difference{0.0f};  // the difference common to all probes (the last bounce), W/m^2
  double share_seconds = 0.0;
  uint64_t cache_cells = 0, cache_direct_cells = 0, cache_edge_cells = 0, cache_edge_profiles = 0, cache_fill_samples = 0,
           cache_fallbacks = 0;
  nlohmann::json to_json() const;
};

struct ProbeOutput {
  ProbeLayout layout;
  std::vector<ProbeSite> sites;  // row-major, H x W
  Image mosaic;                  // (H h) x (W w) RGB radiance
  Image position;                // H x W, X,Y,Z: probe origins (0 where nothing is seen)
  Image normal;                  // H x W, X,Y,Z: the normal each origin is offset along
  Image mask;                    // H x W, Y: 1 for valid probes
  ProbeStats stats;
};

// Places and renders every probe of the view.
ProbeOutput render_probes(const RenderScene& scene, const CameraModel& camera, const Effects& effects,
                          const ProbeSettings& settings);

// Renders probes at given sites (`sites` row-major for settings.layout). With `subset`
// non-empty only those probe indices are rendered (the others stay 0); their values are
// the same as in a full render for kPath (kCache builds its cache from the subset only).
ProbeOutput render_probes_at(const RenderScene& scene, const Effects& effects, std::vector<ProbeSite> sites,
                             const ProbeSettings& settings, const std::vector<int>& subset = {});

// The h x w probe (i, j) cut out of a mosaic.
Image probe_image(const Image& mosaic, const ProbeLayout& layout, int i, int j);

}  // namespace phyir::render
