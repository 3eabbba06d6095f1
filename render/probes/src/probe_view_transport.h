#pragma once
// The light transport the probes of one view share: radiance cache, photons, the lights'
// footprints and exact coverage, and the texel estimator over them (docs/probes-estimator.md,
// "Code map"). Built once before any probe is shaded, read-only while they are. Internal;
// ProbeView owns one.
#include <memory>
#include <vector>

#include "emitter_coverage.h"
#include "emitter_footprints.h"
#include "phyir/render/probe_renderer.h"
#include "probe_texel_estimator.h"
#include "punctual_photons.h"
#include "radiance_cache.h"

namespace phyir::render {

// The probes to shade in tiles of grid neighbours, as indices into the view's list to compute.
using ProbeTiles = std::vector<std::vector<size_t>>;

class ViewTransport {
 public:
  ViewTransport(const RenderScene& scene, const Effects& effects, const ProbeSettings& settings);

  // Cache mode: the cells discovered from one direction per texel of the probes (`todo` indexes
  // `sites`; in shading order), then filled. Its rays, cells and seconds go into *stats.
  void build_cache(const std::vector<ProbeSite>& sites, const std::vector<int>& todo, const ProbeTiles& tiles,
                   ProbeStats* stats);
  // The photons round the computed probes (cache mode, with punctual lights), then the
  // estimator over the cache and photons. Call after build_cache, before shading.
  void build_estimator(const std::vector<ProbeSite>& sites, ProbeStats* stats);

  const TexelEstimator& estimator() const { return *estimator_; }
  const RadianceCache* cache() const { return cache_.get(); }
  const PunctualPhotons& photons() const { return photons_; }
  const EmitterFootprints& footprints() const { return footprints_; }
  const EmitterCoverage& coverage() const { return coverage_; }
  // The floor added to a texel's mean in its spread test (0 without a cache).
  float dark_floor() const { return dark_floor_; }

 private:
  const RenderScene& scene_;
  const Effects& effects_;
  const ProbeSettings& settings_;
  std::unique_ptr<RadianceCache> cache_;
  PunctualPhotons photons_;
  EmitterFootprints footprints_;
  EmitterCoverage coverage_;
  std::unique_ptr<TexelEstimator> estimator_;
  float dark_floor_ = 0.0f;
};

}  // namespace phyir::render
