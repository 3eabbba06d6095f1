#include "phyir/eval/suite.h"

#include <cmath>
#include <map>

#include <spdlog/spdlog.h>

#include "phyir/core/atomic_file.h"
#include "phyir/core/error.h"
#include "phyir/core/progress.h"
#include "phyir/dataset/manifest.h"
#include "phyir/eval/baselines.h"
#include "phyir/eval/figure.h"
#include "phyir/eval/report.h"

namespace fs = std::filesystem;

namespace phyir::eval {

std::vector<nlohmann::json> split_views(const fs::path& gt_dir, const std::string& split) {
  const dataset::Manifest manifest = dataset::read_manifest(gt_dir);
  std::vector<nlohmann::json> out;
  std::map<std::string, int> splits;
  for (const nlohmann::json& v : manifest.views) {
    const std::string s = v.at("split").get<std::string>();
    ++splits[s];
    if (split.empty() || s == split) out.push_back(v);
  }
  if (out.empty()) {
    std::string have;
    for (const auto& [s, n] : splits) have += (have.empty() ? "" : ", ") + s + " (" + std::to_string(n) + ")";
    fail("{}: no view in split '{}' (the manifest has: {})", (gt_dir / "manifest.json").string(), split,
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

}  // namespace

nlohmann::json run_eval(const EvalOptions& o) {
  const std::vector<nlohmann::json> records = split_views(o.gt_dir, o.split);
  std::vector<nlohmann::json> views = records;
  if (o.max_views > 0 && static_cast<int>(views.size()) > o.max_views) views.resize(size_t(o.max_views));
  if (!fs::is_directory(o.pred_dir)) fail("{}: prediction folder missing", o.pred_dir.string());
  // Check every prediction folder exists before any work, so a wrong --pred fails at once.
  for (const nlohmann::json& v : views) {
    const fs::path d = o.pred_dir / v.at("id").get<std::string>();
    if (!fs::is_directory(d))
      fail("{}: missing prediction for view {} (expected PRED/<view id>/ with depth.exr, normal.exr, basecolor.exr, "
           "roughness.exr, metalness.exr)", d.string(), v.at("id").get<std::string>());
    for (const std::string& f : required_prediction_files())
      if (!fs::is_regular_file(d / f)) fail("{}: missing (prediction of view {})", (d / f).string(), v.at("id").get<std::string>());
  }
  fs::create_directories(o.out_dir);

  // Baseline reference: the training split, else the evaluated split itself.
  BaselineStats stats;
  if (o.baselines) {
    std::vector<nlohmann::json> reference;
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
    stats = compute_baseline_stats(o.gt_dir, reference, source);
  }

  MethodResults pred{"prediction", o.model.empty() ? "Prediction (" + o.pred_dir.filename().string() + ")"
                                                   : "PhyIR (ours, " + fs::path(o.model).filename().string() + ")", {}};
  MethodResults constant{"constant_mean", "Constant mean (baseline)", {}};
  MethodResults input_bc{"input_as_basecolor", "Input image as base colour (baseline)", {}};
  std::vector<std::string> ids, scenes;
  std::map<std::string, std::vector<std::string>> missing;
  const fs::path figure_dir = o.out_dir / "figures";
  std::vector<std::string> figure_files;

  Progress progress("eval", views.size(), "views", o.progress);
  for (size_t k = 0; k < views.size(); ++k) {
    const GroundTruthView gt = load_ground_truth(o.gt_dir, views[k]);
    const Prediction p = load_prediction(o.pred_dir / gt.id);
    for (const std::string& f : p.missing) missing[f].push_back(gt.id);
    ids.push_back(gt.id);
    scenes.push_back(gt.scene);
    const bool figure = static_cast<int>(k) < o.figures;
    ViewImages images;
    pred.views.push_back(evaluate_view(gt, p, o.settings, figure ? &images : nullptr));
    if (o.baselines) {
      constant.views.push_back(evaluate_view(gt, constant_mean_prediction(stats, gt, o.settings.radiance_units), o.settings));
      input_bc.views.push_back(evaluate_view(gt, input_as_basecolor_prediction(gt), o.settings));
    }
    if (figure) {
      fs::create_directories(figure_dir);
      std::string name = gt.id;
      for (char& c : name)
        if (c == '/') c = '_';
      const fs::path file = figure_dir / (name + ".png");
      write_side_by_side(file, gt, images);
      figure_files.push_back("figures/" + file.filename().string());
    }
    progress.advance();
  }
  progress.finish();

  nlohmann::json j;
  j["format"] = "phyir-eval";
  j["format_version"] = 1;
  j["dataset"] = o.gt_dir.string();
  j["split"] = o.split;
  j["predictions"] = o.pred_dir.string();
  j["model"] = o.model.empty() ? nlohmann::json(nullptr) : nlohmann::json(o.model);
  j["views"] = ids;
  j["scenes"] = [&] {
    std::map<std::string, int> n;
    for (const auto& s : scenes) ++n[s];
    return nlohmann::json(n);
  }();
  j["settings"] = {{"relight", o.settings.relight},
                   {"relight_positions", o.settings.relight_positions},
                   {"sphere_size", o.settings.sphere.size},
                   {"sphere_spp", o.settings.sphere.spp},
                   {"sphere_max_bounces", o.settings.sphere.max_bounces},
                   {"seed", o.settings.sphere.seed},
                   {"depth_protocol", depth_protocol_name(o.settings.depth_protocol)},
                   {"radiance_units", radiance_units_name(o.settings.radiance_units)}};
  j["baseline_source"] = o.baselines ? nlohmann::json(stats.source) : nlohmann::json(nullptr);
  j["missing_optional_files"] = missing;
  j["figures"] = figure_files;
  nlohmann::json methods;
  methods[pred.key] = method_json(pred, ids, scenes);
  if (o.baselines) {
    methods[constant.key] = method_json(constant, ids, scenes);
    methods[input_bc.key] = method_json(input_bc, ids, scenes);
  }
  j["methods"] = methods;
  j["method_order"] = o.baselines ? nlohmann::json({pred.key, constant.key, input_bc.key}) : nlohmann::json({pred.key});

  write_file_atomic(o.out_dir / "metrics.json", j.dump(2) + "\n");
  write_file_atomic(o.out_dir / "report.md", report_markdown(j));
  return j;
}

}  // namespace phyir::eval
