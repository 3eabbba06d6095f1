// The validation pass: the stage's loss and phyir eval's metrics on the validation views.
#include "validation.h"

#include <ATen/CPUGeneratorImpl.h>

#include <algorithm>
#include <cmath>
#include <mutex>

#include "phyir/core/error.h"
#include "phyir/core/setting_error.h"
#include "phyir/core/log.h"
#include "phyir/core/pcg32.h"
#include "phyir/eval/evaluate_view.h"
#include "phyir/eval/suite.h"
#include "phyir/eval/views.h"
#include "predict.h"

namespace fs = std::filesystem;

namespace phyir::model {

namespace {

// The pass's own seed, apart from the training run's (which the pass saves and restores).
constexpr uint64_t kValidationStream = 0x76616c30;  // "val0"

// Torch's CPU generator state, put back when the scope ends.
class GeneratorScope {
 public:
  GeneratorScope() {
    at::Generator gen = at::detail::getDefaultCPUGenerator();
    std::lock_guard<std::mutex> lock(gen.mutex());
    state_ = gen.get_state();
  }
  ~GeneratorScope() {
    at::Generator gen = at::detail::getDefaultCPUGenerator();
    std::lock_guard<std::mutex> lock(gen.mutex());
    gen.set_state(state_);
  }

 private:
  torch::Tensor state_;
};

// The model's output as the eval library reads a prediction folder, radiance made absolute
// (a run trained on absolute targets, `units` kAbsolute, predicts it already).
eval::Prediction to_eval_prediction(const ModelOutput& p, const view::InputExposure& exposure, view::RadianceUnits units) {
  eval::Prediction e;
  e.depth = tensor_to_image(p.maps.depth[0]);
  e.normal = tensor_to_image(p.maps.normal[0]);
  e.basecolor = tensor_to_image(p.maps.base_color[0].clamp(0.0, 1.0));
  e.roughness = tensor_to_image(p.maps.roughness[0].clamp(0.0, 1.0));
  e.metalness = tensor_to_image(p.maps.metalness[0].clamp(0.0, 1.0));
  if (!p.probes.defined()) return e;
  const double to_absolute = units == view::RadianceUnits::kInput ? 1.0 / exposure.factor() : 1.0;
  e.rerender = tensor_to_image(p.rerender[0] * to_absolute);
  view::ProbeMosaic probes;
  probes.layout = {static_cast<int>(p.probes.size(1)), static_cast<int>(p.probes.size(2)),
                   static_cast<int>(p.probes.size(3)), static_cast<int>(p.probes.size(4))};
  probes.radiance = tensor_to_image(probes_to_mosaic(p.probes * to_absolute)[0]);
  probes.mask = Image(probes.layout.grid_width, probes.layout.grid_height, 1, 1.0f);
  e.probes = std::move(probes);
  return e;
}

// The manifest's views of the split, or none (and why) when there is no such split.
std::vector<view::ViewRecord> split_records(const fs::path& root, const std::string& split, std::string* why) {
  if (split.empty()) {
    *why = "no validation split given";
    return {};
  }
  if (!fs::is_regular_file(root / view::kManifestFile)) {
    *why = (root / view::kManifestFile).string() + " not found";
    return {};
  }
  try {
    return view::read_manifest_views(root, split);
  } catch (const Error& e) {
    *why = e.what();
    return {};
  }
}

}  // namespace

Validator::Validator(const fs::path& root, const ValidationOptions& o, const ModelConfig& config,
                     const torch::Device& device)
    : options_(o), config_(config), device_(device) {
  if (o.every <= 0) return;
  std::string why;
  std::vector<view::ViewRecord> records = split_records(root, o.split, &why);
  if (records.empty()) {
    spdlog::info("validation: off ({})", why);
    return;
  }
  if (o.max_views > 0 && records.size() > static_cast<size_t>(o.max_views)) records.resize(o.max_views);
  for (const view::ViewRecord& r : records) {
    // The same reader as training's (torch_dataset.h's ManifestDataset::get is load_view).
    views_.push_back(load_view(r, config, target_radiance(config)));
    truths_.push_back(std::make_shared<const eval::GroundTruthView>(eval::load_ground_truth(r)));
  }
  higher_is_better(o.best_metric);  // an unknown metric fails before the first epoch
}

bool Validator::due(int epochs_done, int epochs) const {
  return enabled() && (epochs_done % options_.every == 0 || epochs_done == epochs);
}

const std::vector<std::string>& Validator::metric_names() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> n;
    for (const std::string& m : eval::metric_names())
      if (m.rfind("relight_", 0) != 0 && m.rfind("pixels_", 0) != 0 && m != "probes_compared") n.push_back(m);
    return n;
  }();
  return names;
}

bool Validator::higher_is_better(const std::string& metric) {
  if (metric == "val_loss") return false;
  const auto& names = metric_names();
  if (std::find(names.begin(), names.end(), metric) == names.end()) {
    std::string known = "val_loss";
    for (const std::string& n : names) known += ", " + n;
    fail_setting("validation.best_metric", "'{}': expected one of {}", metric, known);
  }
  return eval::higher_is_better(metric);
}

ValidationRecord Validator::run(Networks& nets, const LossWeights& w, StageNetworks stage, StageNetworks trained,
                                uint64_t seed) const {
  GeneratorScope keep_training_generator;
  torch::manual_seed(mix64(seed ^ kValidationStream));
  torch::NoGradGuard no_grad;
  nets.gmnet->eval();
  nets.lnet->eval();
  nets.gsnet->eval();
  ValidationRecord rec;
  eval::EvalSettings settings;
  settings.relight = false;
  std::vector<eval::Metrics> per_view;
  for (size_t k = 0; k < views_.size(); ++k) {
    const Batch b = collate({views_[k]}).to(device_);
    const StepLoss L = stage_loss(nets, config_, w, stage, b);
    rec.loss += L.total.item<double>() / views_.size();
    for (size_t i = 0; i < L.parts.size(); ++i) {
      if (k == 0) rec.loss_parts.emplace_back(L.parts[i].first, 0.0);
      rec.loss_parts[i].second += L.parts[i].second.item<double>() / views_.size();
    }
    const ModelOutput p = predict(nets, config_, b.image, trained.gsnet, trained.lnet);
    per_view.push_back(eval::evaluate_view(*truths_[k],
                                           to_eval_prediction(p, views_[k].exposure, target_radiance(config_)), settings));
  }
  const eval::Metrics mean = eval::mean_metrics(per_view);
  for (const std::string& m : metric_names()) {
    const auto it = mean.find(m);
    rec.metrics.emplace_back(m, it == mean.end() ? std::nan("") : it->second);
  }
  return rec;
}

double metric_value(const ValidationRecord& r, const std::string& metric) {
  if (metric == "val_loss") return r.loss;
  for (const auto& [name, value] : r.metrics)
    if (name == metric) return value;
  return std::nan("");
}

}  // namespace phyir::model
