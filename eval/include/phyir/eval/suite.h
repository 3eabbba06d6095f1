#pragma once
// `phyir eval` as a library call: every view of a split of a dataset against a prediction
// folder, the baselines, the aggregation, and the outputs (metrics.json, report.md, figures).
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "phyir/eval/evaluate_view.h"
#include "phyir/view/view_record.h"

namespace phyir::eval {

// A part of the report computed outside eval (the insertion scores, which need the
// renderer's insertion layer above eval): metrics.json[key] = data, markdown at report.md's end.
struct ReportSection {
  std::string key;
  nlohmann::json data;
  std::string markdown;
};

struct EvalOptions {
  std::filesystem::path gt_dir;     // a `phyir dataset` folder (manifest.json)
  std::string split = "test";
  std::filesystem::path pred_dir;   // PRED/<view id>/ (docs/eval.md)
  std::filesystem::path out_dir;    // report.md, metrics.json, figures/
  std::string model;                // the checkpoint the predictions came from (report only)
  EvalSettings settings;
  int figures = 3;                  // side-by-side PNGs for the first N views
  int baseline_max_views = 64;      // reference views the constant baseline reads (first N)
  bool baselines = true;
  int max_views = 0;                // evaluate only the first N views of the split (0: all)
  bool progress = true;
  std::vector<ReportSection> extra_sections;
};

// The manifest entries of `split` ("" = all) of the dataset, in manifest order; errors when
// the dataset has none (naming the splits it has).
std::vector<view::ViewRecord> split_views(const std::filesystem::path& gt_dir, const std::string& split);

// Runs everything and writes OUT/metrics.json, OUT/report.md and OUT/figures/*.png
// (atomically; metrics.json and report.md last). Returns metrics.json's content.
nlohmann::json run_eval(const EvalOptions& options);

// Mean over views of each metric (views where it is NaN left out); the per-scene breakdown
// uses the same rule.
Metrics mean_metrics(const std::vector<Metrics>& views);

// nlohmann::json of metrics with NaN as null.
nlohmann::json metrics_json(const Metrics& metrics);

}  // namespace phyir::eval
