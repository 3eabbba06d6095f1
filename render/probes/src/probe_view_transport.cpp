#include "probe_view_transport.h"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include "phyir/core/stopwatch.h"
#include "phyir/core/safe_math.h"
#include "phyir/render/streams.h"

namespace phyir::render {

namespace {

// The floor added to a texel's mean in its spread test, as a fraction of a white diffuse surface's
// radiance under the cache's mean irradiance: nearly black texels' noise does not make them hard.
constexpr float kDarkFloorFraction = 0.1f;

}  // namespace

ViewTransport::ViewTransport(const RenderScene& scene, const Effects& effects, const ProbeSettings& settings)
    : scene_(scene), effects_(effects), settings_(settings), footprints_(scene.scene()), coverage_(scene.scene()) {}

void ViewTransport::build_cache(const std::vector<ProbeSite>& sites, const std::vector<int>& todo,
                                const ProbeTiles& tiles, ProbeStats* stats) {
  const Stopwatch watch;
  RadianceCacheSettings cs = settings_.cache;
  cs.seed = stream_key(settings_.seed, Purpose::kCacheSeed);
  cs.progress = settings_.progress;
  cache_ = std::make_unique<RadianceCache>(scene_, effects_, settings_.path, cs);
  const ProbeLayout& layout = settings_.layout;
  const int texels = layout.texels_per_probe();
  const uint64_t probe_seed = stream_key(settings_.seed, Purpose::kProbeSeed);
  tbb::enumerable_thread_specific<RadianceCache::Collector> collectors;
  tbb::enumerable_thread_specific<uint64_t> discovery_rays(0);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, tiles.size(), 1), [&](const tbb::blocked_range<size_t>& r) {
    RadianceCache::Collector& collector = collectors.local();
    uint64_t& rays = discovery_rays.local();
    for (size_t n = r.begin(); n < r.end(); ++n) {
      for (int t = 0; t < texels; ++t) {
        for (size_t k : tiles[n]) {
          const int p = todo[k];
          const uint64_t id = uint64_t(p) * uint64_t(texels) + uint64_t(t);
          const uint64_t key = item_stream_key(probe_seed, id, Purpose::kProbeDiscovery);
          Rng rng = generator(key, Purpose::kProbeDiscovery);
          const Ray ray{sites[size_t(p)].origin,
                        probe_texel_direction(t / layout.res_width, t % layout.res_width, layout.res_height,
                                              layout.res_width, rng.next_2d())};
          SurfaceInteraction si;
          ++rays;
          if (scene_.trace(ray, &si) && !(si.transmission > 0.0f))
            collector.offer(*cache_, cache_point(si, si.shading_normal), stream_key(key, Purpose::kProbeCacheTieBreak));
        }
      }
    }
  });
  std::vector<const RadianceCache::Collector*> list;
  for (const auto& collector : collectors) list.push_back(&collector);
  cache_->build(list, &stats->counters);
  for (uint64_t rays : discovery_rays) stats->counters.rays += rays;
  stats->cache_rays = stats->counters.rays;
  stats->cache_cells = cache_->cell_count();
  stats->cache_direct_cells = cache_->direct_cell_count();
  stats->cache_fill_samples = cache_->fill_samples();
  stats->cache_seconds = watch.seconds();
  dark_floor_ = kDarkFloorFraction * cache_->mean_irradiance_luminance() * kInvPi;
}

void ViewTransport::build_estimator(const std::vector<ProbeSite>& sites, ProbeStats* stats) {
  if (settings_.mode == ProbeMode::kCache && effects_.punctual_lights && settings_.path.max_bounces >= 1) {
    uint64_t rays = 0;
    scenes::Bounds surroundings;  // where the sun's photons matter: round the view's probes
    for (const ProbeSite& site : sites) {
      if (!site.computed()) continue;
      surroundings.extend(site.surface);
      surroundings.extend(site.origin);
    }
    photons_ = PunctualPhotons(scene_, settings_.photons_per_light, settings_.spp, surroundings,
                               stream_key(settings_.seed, Purpose::kProbePhoton), &rays);
    stats->photons = photons_.size();
    stats->photon_rays += rays;
    stats->counters.rays += rays;
  }
  estimator_ = std::make_unique<TexelEstimator>(scene_, effects_, settings_, cache_.get(), &photons_);
}

}  // namespace phyir::render
