#include "bench_probes_summary.h"

#include <cmath>

#include <fmt/format.h>

#include "phyir/core/log.h"

namespace phyir::cli {

ReferenceLighting reference_lighting(const render::ProbeStudy& study, const eval::RelightSettings& settings,
                                     double input_stops) {
  const render::ProbeLayout& l = study.layout();
  ReferenceLighting r;
  r.mean = light_probes(study.reference(), l.res_height, l.res_width, settings);
  const LitProbes half0 = light_probes(study.reference_half(0), l.res_height, l.res_width, settings);
  const LitProbes half1 = light_probes(study.reference_half(1), l.res_height, l.res_width, settings);
  r.halves = lighting_metrics(half0, half1);
  r.input_stops = input_stops;
  r.halves_input = scaled_metrics(r.halves, half0, half1, std::exp2(input_stops));
  eval::RelightSettings other = settings;
  other.seed = settings.seed + 1;
  r.relight_noise = lighting_metrics(light_probes(study.reference(), l.res_height, l.res_width, other), r.mean);
  r.noise = study.reference_noise_per_probe();
  r.pooled_noise = study.reference_noise();
  return r;
}

SummaryRow summary_row(const render::ProbeStudyRow& row, const LightingMetrics& lighting,
                       const LightingMetrics& lighting_input) {
  SummaryRow s;
  s.config = row.setting.name;
  s.cpu_seconds = row.cpu_seconds;
  s.relative_rmse = row.error.relative_rmse;
  s.per_probe = row.per_probe;
  s.lighting = lighting;
  s.lighting_input = lighting_input;
  return s;
}

void log_lighting(const std::string& name, const LightingMetrics& m) {
  spdlog::info("{}: relit spheres MAE diffuse {:.5f} ({:.2f}%), matte silver {:.5f} ({:.2f}%), mirror silver {:.5f} "
               "({:.2f}%); probe log-SSIM {:.4f} ({} probes)",
               name, m.mae[0], 100.0 * m.relative_mae[0], m.mae[1], 100.0 * m.relative_mae[1], m.mae[2],
               100.0 * m.relative_mae[2], m.ssim, m.probes);
}

namespace {

std::string mae_cells(const LightingMetrics& m) {
  std::string out;
  for (size_t k = 0; k < kSphereMaterials; ++k)
    out += fmt::format(" {:.4f} ({:.1f}%) |", m.mae[k], 100.0 * m.relative_mae[k]);
  return out;
}

std::string optional_cell(double v) { return v < 0.0 ? " - |" : fmt::format(" {:.4f} |", v); }

// The lighting metrics in input units: one line per row, then the reference's halves.
std::string input_units_table(const ReferenceLighting& reference, const std::vector<SummaryRow>& rows) {
  std::string md = fmt::format("In input units (radiance times 2^{:+.2f}, the view's input exposure):\n\n",
                               reference.input_stops);
  md += "| config | diffuse MAE | matte silver MAE | mirror silver MAE | log-SSIM |\n";
  md += "| --- | ---: | ---: | ---: | ---: |\n";
  for (const SummaryRow& r : rows)
    md += fmt::format("| {} |{} {:.4f} |\n", r.config, mae_cells(r.lighting_input), r.lighting_input.ssim);
  md += fmt::format("| reference: half vs half |{} {:.4f} |\n", mae_cells(reference.halves_input),
                    reference.halves_input.ssim);
  return md + "\n";
}

}  // namespace

std::string summary_markdown(const std::string& scene, const std::string& grid, const std::string& res,
                             const ReferenceLighting& reference, const std::vector<SummaryRow>& rows) {
  std::string md = fmt::format("### {} ({} grid of {} probes, {} reference probes)\n\n", scene, grid, res,
                               reference.halves.probes);
  md += "| config | CPU s | pooled rel. RMSE | per-probe median | per-probe p90 | bias | noise | diffuse MAE | "
        "matte silver MAE | mirror silver MAE | log-SSIM |\n";
  md += "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n";
  for (const SummaryRow& r : rows)
    md += fmt::format("| {} | {:.1f} | {:.4f} | {:.4f} | {:.4f} |{}{}{} {:.4f} |\n", r.config, r.cpu_seconds,
                      r.relative_rmse, r.per_probe.median, r.per_probe.p90, optional_cell(r.bias),
                      optional_cell(r.noise), mae_cells(r.lighting), r.lighting.ssim);
  md += fmt::format("| reference: noise of the mean; MAE and SSIM half vs half | - | {:.4f} | {:.4f} | {:.4f} | - | "
                    "- |{} {:.4f} |\n",
                    reference.pooled_noise, reference.noise.median, reference.noise.p90, mae_cells(reference.halves),
                    reference.halves.ssim);
  md += fmt::format("| relighting's own noise: the reference's spheres, another seed | - | - | - | - | - | - |{} - |\n",
                    mae_cells(reference.relight_noise));
  return md + "\n" + input_units_table(reference, rows);
}

nlohmann::json reference_json(const ReferenceLighting& reference) {
  const render::ProbeSpread& n = reference.noise;
  return {{"halves", reference.halves.to_json()},
          {"relight_noise", reference.relight_noise.to_json()},
          {"input_exposure_stops", reference.input_stops},
          {"halves_input_units", reference.halves_input.to_json()},
          {"noise", reference.pooled_noise},
          {"per_probe_noise", {{"median", n.median}, {"p90", n.p90}, {"values", n.relative_rmse}}}};
}

}  // namespace phyir::cli
