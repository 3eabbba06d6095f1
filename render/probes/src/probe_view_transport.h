#pragma once
// The light transport the probes of one view share (docs/probes.md, "cache"): built once
// before any probe is shaded, read-only while they are. Internal to the probe renderer;
// ProbeView owns one and keeps the bookkeeping of its passes apart from it.
//
//   radiance cache    its cells discovered by one direction per texel of the view's probes
//   photons           the punctual lights' and the sun's, round the probes
//   footprints        which texels a light may cover, per probe
//   coverage          the exact part of a texel each light covers
//   estimator         a texel direction's radiance from all of the above
#include <memory>
#include <vector>

#include "emitter_coverage.h"
#include "emitter_footprints.h"
#include "phyir/render/probe_renderer.h"
#include "probe_texel_estimator.h"
#include "punctual_photons.h"
#include "radiance_cache.h"

namespace phyir::render {

// The probes to shade, by index into the view's list of probes to compute, in tiles of
// neighbours on the grid.
using ProbeTiles = std::vector<std::vector<size_t>>;

class ViewTransport {
 public:
  ViewTransport(const RenderScene& scene, const Effects& effects, const ProbeSettings& settings);

  // Cache mode: the cache's cells discovered from one direction per texel of the probes
  // (`todo` indexes `sites`; tile by tile, texel by texel across a tile, as the shading
  // goes), then filled. Its rays, cells and seconds go into *stats.
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
  // The radiance below which a texel's spread is not judged against its own mean: a tenth of
  // what a white diffuse surface reflects under the cache's mean irradiance (0 without one).
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
