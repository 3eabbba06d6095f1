#include "phyir/render/probe_renderer.h"

#include "phyir/core/stopwatch.h"
#include "probe_error_target.h"
#include "probe_view.h"

namespace phyir::render {

nlohmann::json ProbeStats::to_json() const {
  return {{"seconds", {{"place", place_seconds}, {"cache", cache_seconds}, {"shade", shade_seconds}, {"share", share_seconds}, {"total", total_seconds}}},
          {"rays", rays()},
          {"paths", counters.paths},
          {"rays_per_second", total_seconds > 0 ? double(rays()) / total_seconds : 0.0},
          {"counts", counts_json()},
          {"supersampled_texels", supersampled_texels},
          {"deep_texels", deep_texels},
          {"balanced_texels", balanced_texels},
          {"shared_texels", shared_texels},
          {"light_texels", light_texels},
          {"light_edge_texels", light_edge_texels},
          {"emission_rays", emission_rays},
          {"photons", {{"photons", photons}, {"rays", photon_rays}, {"texels", photon_texels}}},
          {"negative_texels_clamped", negative_texels},
          {"foot_correction",
           {{"probes", foot_corrections},
            {"common_difference", {foot_common_difference.x, foot_common_difference.y, foot_common_difference.z}}}},
          {"cache", cache_json()},
          {"error", error.to_json()},
          {"nonfinite_samples_caught", counters.nonfinite_samples}};
}

nlohmann::json ProbeStats::counts_json() const {
  return {{"probes", probes}, {"valid", valid}, {"invalid", probes - valid}, {"nothing", nothing},
          {"emitter", emitter}, {"transparent", transparent}, {"computed", computed_probes}};
}

nlohmann::json ProbeStats::cache_json() const {
  return {{"cells", cache_cells},
          {"rays", cache_rays},
          {"cells_with_direct_light", cache_direct_cells},
          {"fill_samples", cache_fill_samples},
          {"fallback_lookups", cache_fallbacks}};
}

nlohmann::json ProbeErrorTarget::to_json() const {
  nlohmann::json j = {{"estimated_relative", estimated}};
  if (target > 0.0)
    j.update({{"target_relative", target}, {"passes", passes}, {"refined_probes", refined_probes},
              {"sigma_factor", sigma_factor}});
  return j;
}

ProbeRenderer::ProbeRenderer(const RenderScene& scene, const Effects& effects, const ProbeSettings& settings)
    : scene_(scene), effects_(effects), settings_(settings) {
  settings.validate();
}

ProbeOutput ProbeRenderer::render(const CameraModel& camera) const {
  const Stopwatch watch;
  std::vector<ProbeSite> sites = place_probes(scene_, camera, settings_.layout, settings_.offset);
  const double place_seconds = watch.seconds();
  ProbeOutput out = render_at(std::move(sites));
  out.stats.place_seconds = place_seconds;
  out.stats.placement_rays = 2 * uint64_t(settings_.layout.probe_count());  // placement + gap check
  out.stats.total_seconds += place_seconds;
  return out;
}

ProbeOutput ProbeRenderer::render_at(std::vector<ProbeSite> sites, const std::vector<int>& subset) const {
  const std::vector<ProbeSite> pass_sites = settings_.target_error > 0.0f ? sites : std::vector<ProbeSite>();
  ProbeOutput out = ProbeView(scene_, effects_, settings_, std::move(sites), subset).run();
  auto render_pass = [&](const ProbeSettings& settings, const std::vector<int>& probes,
                         const std::vector<uint8_t>& choices) {
    return ProbeView(scene_, effects_, settings, pass_sites, probes, &choices).run();
  };
  refine_to_error(settings_, subset, render_pass, &out);
  return out;
}

ProbeOutput render_probes(const RenderScene& scene, const CameraModel& camera, const Effects& effects,
                          const ProbeSettings& settings) {
  return ProbeRenderer(scene, effects, settings).render(camera);
}

ProbeStats& ProbeStats::operator+=(const ProbeStats& o) {
  counters += o.counters;
  placement_rays += o.placement_rays;
  probes += o.probes, valid += o.valid, nothing += o.nothing, emitter += o.emitter, transparent += o.transparent;
  computed_probes += o.computed_probes;
  supersampled_texels += o.supersampled_texels;
  deep_texels += o.deep_texels;
  balanced_texels += o.balanced_texels;
  shared_texels += o.shared_texels;
  light_texels += o.light_texels;
  light_edge_texels += o.light_edge_texels;
  emission_rays += o.emission_rays;
  photon_rays += o.photon_rays;
  photon_texels += o.photon_texels;
  negative_texels += o.negative_texels;
  foot_corrections += o.foot_corrections;
  return *this;
}

}  // namespace phyir::render
