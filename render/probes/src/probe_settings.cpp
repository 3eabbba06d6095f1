#include "phyir/render/probe_settings.h"

#include "phyir/core/setting_error.h"

namespace phyir::render {

ProbeMode parse_probe_mode(const std::string& name) {
  if (name == "path") return ProbeMode::kPath;
  if (name == "cache") return ProbeMode::kCache;
  fail_setting("probe.mode", "'{}' is not one of: cache (the default, shared irradiance cache), path (unbiased reference)",
               name);
}

std::string probe_mode_name(ProbeMode mode) { return mode == ProbeMode::kPath ? "path" : "cache"; }

void ProbeSettings::validate() const {
  layout.validate();
  if (spp <= 0 || spp > 1 << 20) fail_setting("probe.spp", "{} must be between 1 and 2^20", spp);
  // Below 0.1 mm the origin is within a few ulps and ray offsets of room-scale geometry;
  // above 1 m it is no longer "at" the surface.
  if (!(offset >= 1e-4f && offset <= 1.0f)) fail_setting("probe.offset", "{} must be between 1e-4 and 1 metre", offset);
  if (!(cache.cell_size >= 1e-3f && cache.cell_size <= 10.0f))
    fail_setting("probe.cache.cell_size", "{} must be between 1e-3 and 10 metres", cache.cell_size);
  if (cache.samples_per_cell <= 0 || cache.samples_per_cell > 1 << 20)
    fail_setting("probe.cache.samples_per_cell", "{} must be between 1 and 2^20", cache.samples_per_cell);
  if (!(cache.direct_distance_cells >= 0.0f && cache.direct_distance_cells <= 1e6f))
    fail_setting("probe.cache.direct_distance_cells", "{} must be between 0 (never) and 1e6 cells",
                 cache.direct_distance_cells);
  if (hard_spp_factor < 1 || hard_spp_factor > 1024)
    fail_setting("probe.hard_spp_factor", "{} must be between 1 and 1024", hard_spp_factor);
  if (!(balance >= 0.0f && balance <= 64.0f))
    fail_setting("probe.balance", "{} must be between 0 and 64", balance);
  if (!(spread_threshold > 0.0f && spread_threshold <= 1e6f))
    fail_setting("probe.spread_threshold", "{} must be above 0 (and at most 1e6, i.e. never)", spread_threshold);
  // A 9x9 window is already ~20 cm across at the paper's grid: beyond it parallax rejects most texels.
  if (sharing.radius < 0 || sharing.radius > 4)
    fail_setting("probe.sharing.radius", "{} must be between 0 (off) and 4", sharing.radius);
  if (!(sharing.parallax_texels > 0.0f && sharing.parallax_texels <= 100.0f))
    fail_setting("probe.sharing.parallax_texels", "{} must be above 0 and at most 100 texels", sharing.parallax_texels);
  // A million photons from each light: far more than any texel's share needs.
  if (photons_per_light < 0 || photons_per_light > 1 << 20)
    fail_setting("probe.photons_per_light", "{} must be between 0 (none) and 2^20", photons_per_light);
  if (!(chain_end_paths >= 0.0f && chain_end_paths <= 1.0f))
    fail_setting("probe.chain_end_paths", "{} must be a probability, between 0 and 1", chain_end_paths);
  if (!(target_error >= 0.0f && target_error < 10.0f))
    fail_setting("probe.target_error", "{} must be between 0 (one pass) and 10 (a relative error)", target_error);
}

nlohmann::json ProbeSettings::to_json() const {
  nlohmann::json j = {{"grid", {layout.grid_height, layout.grid_width}},
                      {"resolution", {layout.res_height, layout.res_width}},
                      {"mosaic", {layout.mosaic_height(), layout.mosaic_width()}},
                      {"spp", spp},
                      {"mode", probe_mode_name(mode)},
                      {"origin_offset_m", offset},
                      {"seed", seed},
                      {"max_bounces", path.max_bounces},
                      {"light_subpaths", path.light_subpaths},
                      {"punctual_lights", punctual_lights}};
  if (target_error > 0.0f) {
    j["target_error"] = target_error;
    j["progressive"] = progressive;
  }
  if (mode == ProbeMode::kCache) {
    j["cache_cell_m"] = cache.cell_size;
    j["cache_spp"] = cache.samples_per_cell;
    j["cache_direct_cells"] = cache.direct_distance_cells;
    j["hard_spp_factor"] = hard_spp_factor;
    j["glossy_roughness"] = glossy_roughness;
    j["spread_threshold"] = spread_threshold;
    j["balance"] = balance;
    j["share_radius"] = sharing.radius;
    j["share_parallax_texels"] = sharing.parallax_texels;
    j["correct_foot"] = correct_foot;
    j["photons_per_light"] = photons_per_light;
  }
  return j;
}

}  // namespace phyir::render
