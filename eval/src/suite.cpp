#include "phyir/eval/suite.h"

#include <cmath>
#include <map>
#include <utility>

#include <spdlog/spdlog.h>

#include "phyir/core/atomic_file.h"
#include "phyir/core/error.h"
#include "phyir/core/progress.h"
#include "phyir/eval/baselines.h"
#include "phyir/eval/figure.h"
#include "phyir/eval/report.h"

namespace fs = std::filesystem;

namespace phyir::eval {

std::vector<view::ViewRecord> split_views(const fs::path& gt_dir, const std::string& split) {
  const std::vector<view::ViewRecord> all = view::read_manifest_views(gt_dir);
  std::vector<view::ViewRecord> out;
  std::map<std::string, int> splits;
  for (const view::ViewRecord& v : all) {
    ++splits[v.split];
    if (split.empty() || v.split == split) out.push_back(v);
  }
  if (out.empty()) {
    std::string have;
    for (const auto& [s, n] : splits) have += (have.empty() ? "" : ", ") + s + " (" + std::to_string(n) + ")";
    fail("{}: no view in split '{}' (the manifest has: {})", (gt_dir / view::kManifestFile).string(), split,
         have.empty() ? "no views" : have);
  }
  return out;
}

Metrics mean_metrics(const std::vector<Metrics>& views) {
  Metrics mean;
  for (const std::string& name : metric_names()) {
    double sum = 0.0;
    int n = 0;
    for (const Metrics& m : views) {
      const auto it = m.find(name);
      if (it != m.end() && std::isfinite(it->second)) {
        sum += it->second;
        ++n;
      }
    }
    mean[name] = n ? sum / n : std::nan("");
  }
  return mean;
}

nlohmann::json metrics_json(const Metrics& metrics) {
  nlohmann::json j = nlohmann::json::object();
  for (const auto& [k, v] : metrics) j[k] = std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr);
  return j;
}

namespace {

struct MethodResults {
  std::string key, label;
  std::vector<Metrics> views;
};

nlohmann::json method_json(const MethodResults& r, const std::vector<std::string>& ids,
                           const std::vector<std::string>& scenes) {
  nlohmann::json j;
  j["label"] = r.label;
  j["mean"] = metrics_json(mean_metrics(r.views));
  std::map<std::string, std::vector<Metrics>> by_scene;
  nlohmann::json per_view = nlohmann::json::object();
  for (size_t i = 0; i < r.views.size(); ++i) {
    by_scene[scenes[i]].push_back(r.views[i]);
    per_view[ids[i]] = metrics_json(r.views[i]);
  }
  nlohmann::json per_scene = nlohmann::json::object();
  for (const auto& [scene, views] : by_scene) {
    per_scene[scene] = metrics_json(mean_metrics(views));
    per_scene[scene]["views"] = views.size();
  }
  j["per_scene"] = per_scene;
  j["per_view"] = per_view;
  return j;
}

// The views evaluated: the split's, the first max_views of them when that is set.
std::vector<view::ViewRecord> views_to_evaluate(const std::vector<view::ViewRecord>& records, const EvalOptions& o) {
  std::vector<view::ViewRecord> views = records;
  if (o.max_views > 0 && static_cast<int>(views.size()) > o.max_views) views.resize(size_t(o.max_views));
  return views;
}

// Every prediction folder and its required files exist: checked before any work, so a wrong
// prediction folder (pred_dir) fails at once.
void check_predictions(const EvalOptions& o, const std::vector<view::ViewRecord>& views) {
  if (!fs::is_directory(o.pred_dir)) fail("{}: prediction folder missing", o.pred_dir.string());
  for (const view::ViewRecord& v : views) {
    const fs::path d = o.pred_dir / v.id;
    if (!fs::is_directory(d))
      fail("{}: missing prediction for view {} (expected PRED/<view id>/ with depth.exr, normal.exr, basecolor.exr, "
           "roughness.exr, metalness.exr)", d.string(), v.id);
    for (const std::string& f : view::prediction_map_files())
      if (!fs::is_regular_file(d / f)) fail("{}: missing (prediction of view {})", (d / f).string(), v.id);
  }
}

// Baseline reference: the training split, else the evaluated split itself.
BaselineStats baseline_stats(const EvalOptions& o, const std::vector<view::ViewRecord>& records) {
  std::vector<view::ViewRecord> reference;
  std::string source;
  try {
    reference = split_views(o.gt_dir, "train");
    source = "train split";
  } catch (const Error&) {
    reference = records;
    source = "the evaluated split itself ('" + o.split + "'): there is no train split, so this is an oracle constant";
  }
  if (o.baseline_max_views > 0 && static_cast<int>(reference.size()) > o.baseline_max_views)
    reference.resize(size_t(o.baseline_max_views));
  source += ", " + std::to_string(reference.size()) + " views";
  spdlog::info("eval: constant-mean baseline from {}", source);
  return compute_baseline_stats(reference, source);
}

// Writes the view's side-by-side PNG into figure_dir; returns its path relative to the report.
std::string write_figure(const fs::path& figure_dir, const GroundTruthView& gt, const ViewImages& images) {
  fs::create_directories(figure_dir);
  std::string name = gt.id;
  for (char& c : name)
    if (c == '/') c = '_';
  const fs::path file = figure_dir / (name + ".png");
  write_side_by_side(file, gt, images);
  return "figures/" + file.filename().string();
}

// What evaluating the views gathers: each method's metrics per view, the views' ids and
// scenes, the optional prediction files missing (file -> views) and the figures written.
struct ViewResults {
  MethodResults pred;
  MethodResults constant{"constant_mean", "Constant mean (baseline)", {}};
  MethodResults input_bc{"input_as_basecolor", "Input image as base colour (baseline)", {}};
  std::vector<std::string> ids, scenes;
  std::map<std::string, std::vector<std::string>> missing;
  std::vector<std::string> figure_files;
};

std::string prediction_label(const EvalOptions& o) {
  return o.model.empty() ? "Prediction (" + o.pred_dir.filename().string() + ")"
                         : "PhyIR (ours, " + fs::path(o.model).filename().string() + ")";
}

// The views evaluated one by one, in order: the prediction, then the baselines.
class ViewEvaluation {
 public:
  ViewEvaluation(const EvalOptions& o, const BaselineStats& stats) : o_(o), stats_(stats) {}

  ViewResults run(const std::vector<view::ViewRecord>& views) {
    r_.pred = {"prediction", prediction_label(o_), {}};
    Progress progress("eval", views.size(), "views", o_.progress);
    for (size_t k = 0; k < views.size(); ++k) {
      evaluate(views[k], static_cast<int>(k) < o_.figures);
      progress.advance();
    }
    progress.finish();
    return std::move(r_);
  }

 private:
  void evaluate(const view::ViewRecord& view, bool figure) {
    const GroundTruthView gt = load_ground_truth(view);
    const Prediction p = load_prediction(o_.pred_dir / gt.id);
    for (const std::string& f : p.missing) r_.missing[f].push_back(gt.id);
    r_.ids.push_back(gt.id);
    r_.scenes.push_back(gt.scene);
    ViewImages images;
    r_.pred.views.push_back(evaluate_view(gt, p, o_.settings, figure ? &images : nullptr));
    if (o_.baselines) {
      r_.constant.views.push_back(
          evaluate_view(gt, constant_mean_prediction(stats_, gt, o_.settings.radiance_units), o_.settings));
      r_.input_bc.views.push_back(evaluate_view(gt, input_as_basecolor_prediction(gt), o_.settings));
    }
    if (figure) r_.figure_files.push_back(write_figure(o_.out_dir / "figures", gt, images));
  }

  const EvalOptions& o_;
  const BaselineStats& stats_;
  ViewResults r_;
};

nlohmann::json scene_counts(const std::vector<std::string>& scenes) {
  std::map<std::string, int> n;
  for (const auto& s : scenes) ++n[s];
  return nlohmann::json(n);
}

nlohmann::json settings_json(const EvalSettings& s) {
  return {{"relight", s.relight},
          {"relight_positions", s.relight_positions},
          {"sphere_size", s.sphere.size},
          {"sphere_spp", s.sphere.spp},
          {"sphere_max_bounces", s.sphere.max_bounces},
          {"seed", s.sphere.seed},
          {"depth_protocol", depth_protocol_name(s.depth_protocol)},
          {"radiance_units", radiance_units_name(s.radiance_units)}};
}

// metrics.json's content.
nlohmann::json eval_json(const EvalOptions& o, const ViewResults& e, const BaselineStats& stats) {
  nlohmann::json j;
  j["format"] = "phyir-eval";
  j["format_version"] = 1;
  j["dataset"] = o.gt_dir.string();
  j["split"] = o.split;
  j["predictions"] = o.pred_dir.string();
  j["model"] = o.model.empty() ? nlohmann::json(nullptr) : nlohmann::json(o.model);
  j["views"] = e.ids;
  j["scenes"] = scene_counts(e.scenes);
  j["settings"] = settings_json(o.settings);
  j["baseline_source"] = o.baselines ? nlohmann::json(stats.source) : nlohmann::json(nullptr);
  j["missing_optional_files"] = e.missing;
  j["figures"] = e.figure_files;
  nlohmann::json methods;
  methods[e.pred.key] = method_json(e.pred, e.ids, e.scenes);
  if (o.baselines) {
    methods[e.constant.key] = method_json(e.constant, e.ids, e.scenes);
    methods[e.input_bc.key] = method_json(e.input_bc, e.ids, e.scenes);
  }
  j["methods"] = methods;
  j["method_order"] = o.baselines ? nlohmann::json({e.pred.key, e.constant.key, e.input_bc.key}) : nlohmann::json({e.pred.key});
  return j;
}

}  // namespace

nlohmann::json run_eval(const EvalOptions& o) {
  const std::vector<view::ViewRecord> records = split_views(o.gt_dir, o.split);
  const std::vector<view::ViewRecord> views = views_to_evaluate(records, o);
  check_predictions(o, views);
  fs::create_directories(o.out_dir);
  const BaselineStats stats = o.baselines ? baseline_stats(o, records) : BaselineStats{};
  const ViewResults results = ViewEvaluation(o, stats).run(views);
  nlohmann::json j = eval_json(o, results, stats);
  std::string report = report_markdown(j);
  for (const ReportSection& section : o.extra_sections) {
    if (j.contains(section.key)) fail("eval: report section {} would overwrite metrics.json's own", section.key);
    j[section.key] = section.data;
    report += "\n" + section.markdown;
  }
  write_file_atomic(o.out_dir / "metrics.json", j.dump(2) + "\n");
  write_file_atomic(o.out_dir / "report.md", report);
  return j;
}

}  // namespace phyir::eval
