#pragma once
// `phyir bench probes`' summary per probe resolution: the error as users feel it
// (docs/probes_lighting_metrics.md), one line per configuration beside the reference's own
// noise on the same measure, logged and written as a markdown table (probes_summary.md).
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "bench_probes_lighting.h"
#include "phyir/render/probe_study.h"

namespace phyir::cli {

// The reference's side: its probes relit, and its own noise on every measure.
struct ReferenceLighting {
  LitProbes mean;             // the reference (mean of its halves)
  LightingMetrics halves;     // half 0 against half 1: each half has twice the mean's variance
  // The mean's spheres relit under another seed against its own: the relighting's own
  // Monte-Carlo noise, which every MAE above includes (the probes differ, so the same seed
  // does not cancel it).
  LightingMetrics relight_noise;
  double input_stops = 0.0;      // the view's input exposure (bench_probes_exposure.h)
  LightingMetrics halves_input;  // `halves` in input units (times 2^input_stops)
  render::ProbeSpread noise;  // per-probe relative noise of the mean (probe_study.h)
  double pooled_noise = 0.0;
};
ReferenceLighting reference_lighting(const render::ProbeStudy& study, const eval::RelightSettings& settings,
                                     double input_stops);

struct SummaryRow {
  std::string config;
  double cpu_seconds = 0.0;
  double relative_rmse = 0.0;
  render::ProbeSpread per_probe;
  double bias = -1.0, noise = -1.0;  // from the breakdown's total; negative without a seed pair
  LightingMetrics lighting;        // in absolute units
  LightingMetrics lighting_input;  // in input units
};
SummaryRow summary_row(const render::ProbeStudyRow& row, const LightingMetrics& lighting,
                       const LightingMetrics& lighting_input);

// The log lines of one row (or of the reference, as "reference halves").
void log_lighting(const std::string& name, const LightingMetrics& m);

// The markdown tables: the probe error and the lighting metrics in absolute units, one line
// per row, then the reference's; the lighting metrics in input units.
std::string summary_markdown(const std::string& scene, const std::string& grid, const std::string& res,
                             const ReferenceLighting& reference, const std::vector<SummaryRow>& rows);

// JSON of the reference's side (probes.json's "reference_lighting").
nlohmann::json reference_json(const ReferenceLighting& reference);

}  // namespace phyir::cli
