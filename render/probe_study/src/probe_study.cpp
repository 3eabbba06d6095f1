#include "phyir/render/probe_study.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "phyir/core/image_io.h"
#include "phyir/core/log.h"
#include "phyir/core/machine.h"
#include "phyir/core/setting_error.h"
#include "phyir/render/probe_study_breakdown.h"
#include "phyir/render/rng.h"

namespace phyir::render {

namespace fs = std::filesystem;

bool same_but_seed(const ProbeSettings& a, const ProbeSettings& b) {
  return a.mode == b.mode && a.spp == b.spp && a.cache.samples_per_cell == b.cache.samples_per_cell &&
         a.cache.cell_size == b.cache.cell_size && a.cache.direct_distance_cells == b.cache.direct_distance_cells &&
         a.spread_threshold == b.spread_threshold && a.sharing.radius == b.sharing.radius &&
         a.sharing.parallax_texels == b.sharing.parallax_texels && a.target_error == b.target_error &&
         a.progressive == b.progressive && a.seed != b.seed;
}

ProbeStudy::ProbeStudy(const RenderScene& scene, const CameraModel& camera, const Effects& effects,
                       ProbeStudyOptions options)
    : scene_(scene), effects_(effects), options_(std::move(options)) {
  const ProbeSettings& s = options_.base;
  s.validate();
  sites_ = place_probes(scene_, camera, s.layout, s.offset);
  for (const ProbeSite& site : sites_) computed_ += site.computed() ? 1 : 0;
  pick_subset();
  const ProbeLayout& l = s.layout;
  std::string which = std::to_string(subset_.size()) + "probes";
  if (!options_.probe_indices.empty()) {
    which = "probes";
    for (int p : subset_) which += "-" + std::to_string(p);
  }
  tag_ = fmt::format("{}x{}_{}x{}_{}spp_{}_seed{}", l.grid_height, l.grid_width, l.res_height, l.res_width,
                     options_.reference_spp, which, s.seed);
}

// A random subset of valid probes, the same for every setting; or the probes given.
void ProbeStudy::pick_subset() {
  const ProbeLayout& l = options_.base.layout;
  std::vector<int> valid;
  for (size_t p = 0; p < sites_.size(); ++p)
    if (sites_[p].valid()) valid.push_back(int(p));
  // A room that is all light (every surface emits) has computed probes but no valid one.
  if (valid.empty()) {
    for (size_t p = 0; p < sites_.size(); ++p)
      if (sites_[p].computed()) valid.push_back(int(p));
    if (!valid.empty())
      spdlog::warn("{}: no valid probe in the {}x{} grid; measuring on computed ones (on emitters or glass)",
                   options_.scene, l.grid_height, l.grid_width);
  }
  if (valid.empty()) fail("{}: no probe computed in the {}x{} grid", options_.scene, l.grid_height, l.grid_width);
  Rng pick(0x5eed + options_.base.seed, 3);
  subset_ = valid;
  const size_t n = std::min(subset_.size(), size_t(std::max(options_.reference_probes, 1)));
  for (size_t k = 0; k < n; ++k) std::swap(subset_[k], subset_[k + pick.next_u32() % (subset_.size() - k)]);
  subset_.resize(n);
  if (!options_.probe_indices.empty()) {
    subset_.clear();
    for (int p : options_.probe_indices) {
      if (p < 0 || size_t(p) >= sites_.size() || !sites_[size_t(p)].valid())
        fail_setting("probe_indices", "{} is not a valid probe of the {}x{} grid", p, l.grid_height, l.grid_width);
      subset_.push_back(p);
    }
  }
  std::sort(subset_.begin(), subset_.end());
}

nlohmann::json ProbeStudy::subset_json() const {
  const int grid_width = options_.base.layout.grid_width;
  nlohmann::json probes = nlohmann::json::array();
  for (int p : subset_) {
    const ProbeSite& site = sites_[size_t(p)];
    probes.push_back({{"index", p}, {"i", p / grid_width}, {"j", p % grid_width},
                      {"origin", {site.origin.x, site.origin.y, site.origin.z}},
                      {"normal", {site.normal.x, site.normal.y, site.normal.z}}});
  }
  return probes;
}

void ProbeStudy::make_reference(const fs::path& cache) {
  const ProbeSettings& s = options_.base;
  for (int h = 0; h < 2; ++h) {
    const fs::path path = cache / ("reference_" + tag_ + "_half" + std::to_string(h) + ".exr");
    const fs::path stderr_path = cache / ("reference_" + tag_ + "_half" + std::to_string(h) + "_stderr.exr");
    if (fs::exists(path)) {
      halves_[h] = read_image(path);
      if (fs::exists(stderr_path)) half_stderr_[h] = read_image(stderr_path);
      spdlog::info("reusing {}", path.string());
      continue;
    }
    ProbeSettings r = s;
    r.mode = ProbeMode::kPath;
    r.spp = std::max(options_.reference_spp / 2, 1);
    r.seed = s.seed + 1000 + uint64_t(h);
    r.progress = true;
    spdlog::info("reference half {}: {} probes, {}x{} texels, {} spp, path mode", h, subset_.size(),
                 s.layout.res_height, s.layout.res_width, r.spp);
    const ProbeOutput out = ProbeRenderer(scene_, effects_, r).render_at(sites_, subset_);
    halves_[h] = probe_strip(out.mosaic, s.layout, subset_);
    half_stderr_[h] = probe_strip(out.standard_error, s.layout, subset_);
    write_image(path, halves_[h]);
    write_image(stderr_path, half_stderr_[h]);
  }
  if (!half_stderr_[0].empty() && !half_stderr_[1].empty()) {
    reference_stderr_ = half_stderr_[0];
    for (size_t k = 0; k < reference_stderr_.pixels.size(); ++k)
      reference_stderr_.pixels[k] = 0.5f * std::hypot(half_stderr_[0].pixels[k], half_stderr_[1].pixels[k]);
  }
  reference_ = halves_[0];
  for (size_t k = 0; k < reference_.pixels.size(); ++k)
    reference_.pixels[k] = 0.5f * (halves_[0].pixels[k] + halves_[1].pixels[k]);
  reference_noise_ = image_error(halves_[0], halves_[1]).relative_rmse / 2.0;
  reference_noise_per_probe_ =
      probe_spread(per_probe_relative_rmse(halves_[0], halves_[1], reference_, s.layout.res_width, 0.5));
  spdlog::info("reference noise (relative RMSE of the mean of two halves): {:.4f}", reference_noise_);
  classes_ = classify_texels(scene_, sites_, subset_, s.layout, s.glossy_roughness);
}

ProbeStudyRow ProbeStudy::measure(const ProbeStudySetting& setting) const {
  const ProbeSettings& t = setting.settings;
  t.validate();
  ProbeStudyRow row;
  row.setting = setting;
  row.extrapolated = t.mode == ProbeMode::kPath || options_.subset_only;
  const double cpu_start = process_cpu_seconds();
  const ProbeRenderer renderer(scene_, effects_, t);
  const ProbeOutput out = row.extrapolated ? renderer.render_at(sites_, subset_) : renderer.render_at(sites_);
  row.cpu_seconds = process_cpu_seconds() - cpu_start;
  row.seconds = out.stats.total_seconds;
  row.rays = double(out.stats.counters.rays);
  if (row.extrapolated) {
    const double scale = double(computed_) / double(subset_.size());
    row.seconds *= scale;
    row.cpu_seconds *= scale;
    row.rays *= scale;
  }
  row.stats = out.stats;
  row.strip = probe_strip(out.mosaic, t.layout, subset_);
  row.error = image_error(row.strip, reference_);
  row.per_probe = probe_spread(per_probe_relative_rmse(row.strip, reference_, reference_, t.layout.res_width));
  row.strip_stderr = probe_strip(out.standard_error, t.layout, subset_);
  if (!reference_stderr_.empty())
    row.calibration = probe_calibration(row.strip, row.strip_stderr, reference_, reference_stderr_);
  return row;
}

nlohmann::json ProbeStudy::breakdown(const ProbeStudyRow& row, const ProbeStudyRow* other) const {
  return error_breakdown(row.strip, other ? &other->strip : nullptr, reference_, halves_, classes_, subset_, sites_,
                         options_.base.layout, scene_);
}

}  // namespace phyir::render
