// One stage's training run (trainer.h): settings, networks, data, epochs, validation, logs.
#include "trainer.h"

#include <algorithm>
#include <cstdlib>
#include <optional>

#include "augment.h"
#include "batch_share.h"
#include "data_parallel.h"
#include "device.h"
#include "phyir/core/error.h"
#include "phyir/view/view_files.h"
#include "phyir/core/setting_error.h"
#include "phyir/core/log.h"
#include "phyir/core/stopwatch.h"

namespace fs = std::filesystem;
using nlohmann::json;

namespace phyir::model {

namespace {

json augment_to_json(const AugmentOptions& a) {
  return {{"enabled", a.enabled}, {"rotate", a.rotate}, {"mirror", a.mirror},
          {"exposure_min_stops", a.exposure_min_stops}, {"exposure_max_stops", a.exposure_max_stops}};
}

json validation_to_json(const ValidationOptions& v) {
  return {{"split", v.split}, {"every", v.every}, {"max_views", v.max_views}, {"best_metric", v.best_metric}};
}

}  // namespace

bool BestSoFar::better(double candidate, bool higher_is_better) const {
  if (std::isnan(candidate)) return false;
  if (std::isnan(value)) return true;
  return higher_is_better ? candidate > value : candidate < value;
}

json BestSoFar::to_json() const {
  if (std::isnan(value)) return nullptr;
  return {{"metric", metric}, {"value", value}, {"epoch", epoch}, {"global_step", step}};
}

Trainer::Trainer(const TrainOptions& o)
    : o_(o), stage_name_(stage_name(o.stage)), defaults_(stage_defaults(o.stage)), stage_(StageNetworks::of(o.stage)) {}

TrainSummary Trainer::run() {
  settle_settings();
  join_ranks();
  build_networks();
  load_data();
  summary_.checkpoint = checkpoint_path_.string();
  start_time_ = Stopwatch();
  for (int epoch = start_epoch_; epoch < o_.epochs; ++epoch)
    if (!run_epoch(epoch)) break;
  summary_.steps = global_step_;
  if (!summary_.epoch_losses.empty()) {
    summary_.first_loss = summary_.epoch_losses.front();
    summary_.last_loss = summary_.epoch_losses.back();
  }
  if (lead() && !fs::is_regular_file(checkpoint_path_))
    save_checkpoint(checkpoint_path_, meta(start_epoch_, start_batch_), *nets_, opt_.get());
  if (lead()) write_summary();
  // No rank reports success before rank 0's last files are written.
  if (group_) group_->barrier("the end of training");
  if (!lead()) return summary_;
  spdlog::info("train {}: {} steps, mean loss first epoch {:.5g}, last epoch {:.5g}; checkpoint {}", stage_name_,
               summary_.steps, summary_.first_loss, summary_.last_loss, checkpoint_path_.string());
  return summary_;
}

// --- Setup ------------------------------------------------------------------------------------

void Trainer::settle_settings() {
  if (o_.epochs < 1) fail_setting("epochs", "{} must be at least 1", o_.epochs);
  if (o_.out_dir.empty()) fail_setting("out_dir", "an output folder is required");
  if (o_.augment.exposure_min_stops > o_.augment.exposure_max_stops)
    fail_setting("augment.exposure_min_stops", "{},{}: the first bound is above the second",
                 o_.augment.exposure_min_stops, o_.augment.exposure_max_stops);
  Validator::higher_is_better(o_.validation.best_metric);  // an unknown metric fails now
  device_ = parse_device(o_.device);
  out_ = o_.out_dir;
  fs::create_directories(out_);
  checkpoint_path_ = out_ / "checkpoint.pt";
  if (o_.resume && !fs::is_regular_file(checkpoint_path_)) fail_setting("resume", "{} not found", checkpoint_path_.string());
  // A resumed run keeps its learning rate, batch size and weights unless they are given again.
  resumed_ = o_.resume ? load_checkpoint(checkpoint_path_.string(), nullptr, nullptr, false) : json();
  // Before any state is loaded: another stage's optimiser has other parameter groups.
  if (o_.resume && resumed_.value("stage", std::string()) != stage_name_)
    fail_setting("resume", "{} is a '{}' checkpoint, not '{}' (start the stage from it as its init checkpoint instead)",
                 checkpoint_path_.string(), resumed_.value("stage", std::string("?")), stage_name_);
  lr_ = o_.learning_rate > 0 ? o_.learning_rate
        : o_.resume          ? resumed_.at("learning_rate").get<double>()
                             : defaults_.learning_rate;
  batch_size_ = o_.batch_size > 0 ? o_.batch_size : o_.resume ? resumed_.at("batch_size").get<int>() : defaults_.batch_size;
  weights_ = o_.custom_weights ? o_.weights : defaults_.weights;
  if (o_.resume && !o_.custom_weights) weights_ = weights_from_json(resumed_.at("weights"));
  if (o_.probe_loss_weight != "none" && o_.probe_loss_weight != "stderr")
    fail_setting("probe_loss_weight", "'{}': none or stderr", o_.probe_loss_weight);
  weights_.probe_stderr = o_.probe_loss_weight == "stderr";
  if (o_.resume && resumed_.contains("augment") && resumed_["augment"] != augment_to_json(o_.augment))
    spdlog::warn("resuming: augmentation {} differs from the checkpoint's {}: the run will not equal an "
                 "uninterrupted one", augment_to_json(o_.augment).dump(), resumed_["augment"].dump());
  // The configuration: from the checkpoint being resumed or initialised from, else the options.
  config_ = o_.config;
  if (o_.resume) config_ = config_from_json(resumed_.at("config"));
  else if (!o_.init.empty()) config_ = read_checkpoint_config(o_.init);
  // The targets' unit may change at an init checkpoint (GMNet's maps have none, so one GMNet stage can start
  // both arms of the exposure study); a resume keeps its run's.
  if (!o_.target_units.empty() && o_.target_units != config_.target_units) {
    if (o_.resume)
      fail_setting("target_units", "{} differs from the resumed checkpoint's {} (a resumed run keeps its unit)",
                   o_.target_units, config_.target_units);
    if (!o_.init.empty())
      spdlog::info("target units {}: replace {}'s {}", o_.target_units, o_.init, config_.target_units);
  }
  if (!o_.target_units.empty()) config_.target_units = o_.target_units;
  check_config(config_);
}

void Trainer::join_ranks() {
  const DistributedOptions& d = o_.distributed;
  if (d.world_size <= 1) return;
  spdlog::info("train {}: rank {} of {} joining at {}", stage_name_, d.rank, d.world_size, d.rendezvous);
  group_ = ProcessGroup::join(d);
  rank_ = group_->rank();
  ranks_ = group_->size();
  // A cuda device without an index: the ranks of a node spread over its GPUs.
  if (device_.is_cuda() && !device_.has_index()) {
    device_ = torch::Device(torch::kCUDA, static_cast<c10::DeviceIndex>(rank_ % torch::cuda::device_count()));
    spdlog::info("train {}: rank {} trains on {}", stage_name_, rank_, device_.str());
  }
}

void Trainer::build_networks() {
  torch::manual_seed(o_.seed);
  nets_ = std::make_unique<Networks>(config_);
  trained_ = json::object({{"gmnet", false}, {"lnet", false}, {"gsnet", false}});
  if (!o_.init.empty() && !o_.resume) trained_ = load_checkpoint(o_.init, nets_.get(), nullptr, false).value("trained", trained_);
  if (!o_.encoder_weights.empty() && !o_.resume && o_.init.empty()) nets_->gmnet->load_encoder(o_.encoder_weights);
  // Before the optimiser exists, so its state is made (or loaded: load_checkpoint) on the device.
  nets_->to(device_);
  if ((o_.stage == Stage::kLNet || o_.stage == Stage::kGSNet) && !trained_.value("gmnet", false))
    spdlog::warn("stage {}: GMNet is frozen but untrained (start it from a gmnet checkpoint)", stage_name_);
  // The stage's networks train; the others are frozen (eval mode, no gradients).
  std::vector<torch::Tensor> params;
  auto collect = [&](torch::nn::Module& m, bool on) {
    for (auto& p : m.parameters()) {
      p.set_requires_grad(on);
      if (on) params.push_back(p);
    }
  };
  collect(*nets_->gmnet, stage_.gmnet);
  collect(*nets_->lnet, stage_.lnet);
  collect(*nets_->gsnet, stage_.gsnet);
  opt_ = std::make_unique<torch::optim::Adam>(params, torch::optim::AdamOptions(lr_));
  best_.metric = o_.validation.best_metric;
  if (group_) broadcast_networks(*group_, *nets_);
  if (!o_.resume) return;
  const json m = load_checkpoint(checkpoint_path_.string(), nets_.get(), opt_.get(), true, device_);
  start_epoch_ = m.at("epoch");
  start_batch_ = m.at("batch");
  global_step_ = m.at("global_step");
  // Resumed mid-epoch: the epoch's mean loss continues over the steps before the stop.
  epoch_loss_sum_ = start_batch_ > 0 ? m.value("epoch_loss_sum", 0.0) : 0.0;
  epoch_steps_ = start_batch_ > 0 ? m.value("epoch_steps", int64_t{0}) : 0;
  trained_ = m.at("trained");
  const json best = m.value("best", json());
  if (best.is_object() && best.at("metric") == best_.metric) {
    best_.value = best.at("value");
    best_.epoch = best.at("epoch");
    best_.step = best.at("global_step");
  } else if (best.is_object()) {
    spdlog::warn("resuming: the checkpoint's best is by {}, this run keeps the best by {} from now on",
                 best.at("metric").get<std::string>(), best_.metric);
  }
}

void Trainer::load_data() {
  const view::RadianceUnits units = target_radiance(config_);
  // Only LNet's stages read the probes (the gmnet and gsnet losses never look at them).
  ManifestDataset views =
      ManifestDataset::for_training(o_.data_dir, o_.split, o_.max_views, config_, units, stage_.lnet);
  // One view read now: a stage that needs probes fails before the first step, not in a worker.
  if (stage_.lnet && !views.get(0).probes.defined())
    fail("stage {}: {} has no {} (render the dataset with probes)", stage_name_, views.folder(0).string(),
         view::kProbesFile);
  if (stage_.lnet && weights_.probe_stderr && !views.get(0).probe_stderr.defined())
    fail("stage {}: probe loss weighted by standard error: {} has no {} (render the probes again, or train "
         "unweighted)", stage_name_, views.folder(0).string(), view::kProbeStderrFile);
  views_ = static_cast<int64_t>(views.size().value());
  batch_ = std::min<int64_t>(batch_size_, views_);
  batches_per_epoch_ = global_batches(views_, batch_, ranks_);
  if (batches_per_epoch_ * batch_ < views_)
    spdlog::warn("train {}: the last {} view(s) of each epoch are fewer than the {} ranks and are left out of "
                 "it (a different view each epoch)", stage_name_, views_ - batches_per_epoch_ * batch_, ranks_);
  yaw_divisions_ = yaw_divisions(config_);
  stream_ = std::make_unique<BatchStream>(
      TrainingBatches(std::move(views), o_.augment, yaw_divisions_, o_.seed, units),
      StreamOptions{o_.workers, o_.prefetch});
  const json saved_schedule = o_.resume ? resumed_.value("schedule", json()) : json();
  schedule_ = make_schedule(o_.schedule, saved_schedule, lr_, o_.epochs, batches_per_epoch_);
  // Rank 0 alone validates (the others wait for it at the next step).
  ValidationOptions validation = o_.validation;
  if (!lead()) validation.split.clear();
  validator_ = std::make_unique<Validator>(o_.data_dir, validation, config_, device_);
  if (group_) {
    int64_t gradients = 0;
    for (const torch::Tensor& p : opt_->parameters()) gradients += p.numel();
    spdlog::info("train {}: rank {} of {} reads {} of each batch's {} views; {} gradients ({:.1f} MB) all-reduced a "
                 "step", stage_name_, rank_, ranks_, rank_batch(batch_, rank_, ranks_), batch_, gradients,
                 4e-6 * static_cast<double>(gradients));
  }
  if (!lead()) return;
  spdlog::info("train {}: {} views (streamed: {} workers, {} batches ahead), batch {}, {} steps/epoch, lr {} ({}), "
               "{} threads, device {}, input {}x{}, render {}x{}, probes {}x{}, augmentation {}, validation {}",
               stage_name_, views_, o_.workers, o_.workers > 0 ? o_.prefetch : 0, batch_, batches_per_epoch_, lr_,
               schedule_.kind, o_.threads, device_.str(), config_.input_width,
               config_.input_height, config_.render_width, config_.render_height, config_.probe_width,
               config_.probe_height, o_.augment.enabled ? "on" : "off",
               validator_->enabled() ? fmt::format("{} views every {} epochs", validator_->size(), o_.validation.every)
                                     : std::string("off"));
  step_log_ = std::make_unique<CsvLog>(out_ / "train_log.csv", o_.resume, global_step_);
  if (validator_->enabled()) val_log_ = std::make_unique<CsvLog>(out_ / "val_log.csv", o_.resume, global_step_);
}

// --- Epochs and steps ---------------------------------------------------------------------------

bool Trainer::run_epoch(int epoch) {
  if (epoch != start_epoch_ || start_batch_ == 0) {
    epoch_loss_sum_ = 0.0;
    epoch_steps_ = 0;
  }
  set_modes(true);
  bool stopped = false;  // max_steps reached inside the epoch
  int64_t bi = epoch == start_epoch_ ? start_batch_ : 0;
  // The epoch's order depends only on (seed, epoch), so a resumed run sees the same batches.
  // Each rank reads its slice of every global batch (data_parallel.h); one process reads them all.
  const std::vector<size_t> order =
      rank_order(epoch_order(static_cast<size_t>(views_), o_.seed, epoch), batch_, rank_, ranks_);
  stream_->run_epoch(epoch, order, bi, rank_batch(batch_, rank_, ranks_), [&](Batch b) {
    run_step(epoch, bi, b.to(device_));
    const bool at_limit = o_.max_steps > 0 && global_step_ >= o_.max_steps;
    if (bi + 1 == batches_per_epoch_) return false;  // the epoch's end: below
    // Resume point: the next batch of this epoch.
    if (lead() && (at_limit || (o_.checkpoint_every > 0 && global_step_ % o_.checkpoint_every == 0)))
      save_checkpoint(checkpoint_path_, meta(epoch, bi + 1), *nets_, opt_.get());
    ++bi;
    stopped = at_limit;
    return !at_limit;
  });
  if (stopped) {
    summary_.epoch_losses.push_back(epoch_loss_sum_ / static_cast<double>(epoch_steps_));
    return false;
  }
  if (epoch_steps_ > 0) summary_.epoch_losses.push_back(epoch_loss_sum_ / static_cast<double>(epoch_steps_));
  if (validator_->due(epoch + 1, o_.epochs)) validate(epoch + 1);
  if (lead()) save_checkpoint(checkpoint_path_, meta(epoch + 1, 0), *nets_, opt_.get());
  summary_.epochs_done = epoch + 1;
  return !(o_.max_steps > 0 && global_step_ >= o_.max_steps);
}

double Trainer::run_step(int epoch, int64_t bi, const Batch& b) {
  const Stopwatch watch;
  const double lr = schedule_.at(global_step_);
  for (auto& group : opt_->param_groups()) static_cast<torch::optim::AdamOptions&>(group.options()).lr(lr);
  // With ranks, the loss is the global batch's (batch_share.h): the same value on every rank.
  std::optional<BatchShare> share;
  if (group_) share.emplace(*group_, rank_slice(std::min(batch_, views_ - bi * batch_), rank_, ranks_).first);
  const StepLoss L = stage_loss(*nets_, config_, weights_, stage_, b);
  const double loss = L.total.item<double>();
  // The NaN check of every step: stop before the optimiser spreads it into the weights.
  if (!std::isfinite(loss))
    fail("train {}: the loss is {} at epoch {} step {} (global step {}): {}. Stopped; the last good checkpoint is {} "
         "(try a lower learning rate)",
         stage_name_, loss, epoch + 1, bi + 1, global_step_ + 1, format_parts(L), checkpoint_path_.string());
  opt_->zero_grad();
  L.total.backward();
  share.reset();
  if (group_) average_gradients(*group_, opt_->parameters());
  opt_->step();
  ++global_step_;
  epoch_loss_sum_ += loss;
  ++epoch_steps_;
  log_step(epoch, bi, loss, L, lr, watch.seconds());
  return loss;
}

void Trainer::log_step(int epoch, int64_t bi, double loss, const StepLoss& L, double lr, double step_seconds) {
  if (!lead()) return;
  if (!step_log_->has_header()) {
    std::vector<std::string> columns = {"stage", "epoch", "global_step", "loss"};
    for (const auto& part : L.parts) columns.push_back(part.first);
    columns.insert(columns.end(), {"lr", "seconds"});
    step_log_->header(columns);
  }
  std::vector<std::string> row = {stage_name_, std::to_string(epoch + 1), std::to_string(global_step_), csv_number(loss)};
  for (const auto& part : L.parts) row.push_back(csv_number(part.second.item<double>()));
  row.insert(row.end(), {csv_number(lr), fmt::format("{:.3f}", start_time_.seconds())});
  step_log_->row(row);
  if (o_.progress)
    spdlog::info("[{}] epoch {}/{} step {}/{} loss {:.5g} ({}) lr {:.3g} {:.2f} s/step", stage_name_, epoch + 1,
                 o_.epochs, bi + 1, batches_per_epoch_, loss, format_parts(L), lr, step_seconds);
}

void Trainer::set_modes(bool training) {
  nets_->gmnet->train(training && stage_.gmnet);
  nets_->lnet->train(training && stage_.lnet);
  nets_->gsnet->train(training && stage_.gsnet);
}

// --- Validation, checkpoints, summary -----------------------------------------------------------

void Trainer::validate(int epoch_done) {
  const Stopwatch watch;
  StageNetworks trained = stage_;
  trained.gmnet = true;
  trained.lnet = trained.lnet || trained_.value("lnet", false);
  trained.gsnet = trained.gsnet || trained_.value("gsnet", false);
  ValidationRecord rec = validator_->run(*nets_, weights_, stage_, trained, o_.seed);
  set_modes(true);
  rec.epoch = epoch_done;
  rec.step = global_step_;
  const double train_loss = epoch_steps_ > 0 ? epoch_loss_sum_ / static_cast<double>(epoch_steps_) : std::nan("");
  if (!val_log_->has_header()) {
    std::vector<std::string> columns = {"stage", "epoch", "global_step", "train_loss", "val_loss"};
    for (const auto& part : rec.loss_parts) columns.push_back("val_" + part.first);
    for (const auto& metric : rec.metrics) columns.push_back(metric.first);
    columns.insert(columns.end(), {"lr", "seconds"});
    val_log_->header(columns);
  }
  std::vector<std::string> row = {stage_name_, std::to_string(epoch_done), std::to_string(global_step_),
                                  csv_number(train_loss), csv_number(rec.loss)};
  for (const auto& part : rec.loss_parts) row.push_back(csv_number(part.second));
  for (const auto& metric : rec.metrics) row.push_back(csv_number(metric.second));
  // The rate of the epoch's last step.
  row.insert(row.end(), {csv_number(schedule_.at(std::max<int64_t>(0, global_step_ - 1))),
                         fmt::format("{:.3f}", start_time_.seconds())});
  val_log_->row(row);
  const double value = metric_value(rec, best_.metric);
  const bool improved = best_.better(value, Validator::higher_is_better(best_.metric));
  if (improved) {
    best_.value = value;
    best_.epoch = epoch_done;
    best_.step = global_step_;
    save_checkpoint(out_ / "best.pt", meta(epoch_done, 0), *nets_, nullptr);
  }
  spdlog::info("[{}] validation after epoch {}: loss {:.5g}{}{} ({} views, {:.1f} s)", stage_name_, epoch_done,
               rec.loss, best_.metric == "val_loss" ? std::string() : fmt::format(", {} {:.5g}", best_.metric, value),
               improved ? ", best so far: best.pt" : fmt::format(" (best {:.5g} at epoch {})", best_.value, best_.epoch),
               validator_->size(), watch.seconds());
  summary_.validations.push_back(std::move(rec));
}

json Trainer::meta(int epoch, int64_t batch) const {
  json t = trained_;
  if (stage_.gmnet) t["gmnet"] = true;
  if (stage_.lnet) t["lnet"] = true;
  if (stage_.gsnet) t["gsnet"] = true;
  return json{{"format", "phyir-checkpoint-1"}, {"stage", stage_name_}, {"config", config_to_json(config_)},
              {"epoch", epoch}, {"batch", batch}, {"global_step", global_step_}, {"seed", o_.seed},
              {"learning_rate", lr_}, {"batch_size", batch_}, {"weights", weights_to_json(weights_)},
              {"trained", t}, {"schedule", schedule_.to_json()}, {"augment", augment_to_json(o_.augment)},
              {"validation", validation_to_json(o_.validation)}, {"best", best_.to_json()},
              {"epoch_loss_sum", batch > 0 ? epoch_loss_sum_ : 0.0}, {"epoch_steps", batch > 0 ? epoch_steps_ : 0},
              {"ranks", ranks_}};
}

void Trainer::write_summary() {
  json log = meta(summary_.epochs_done, 0);
  log["epochs"] = o_.epochs;
  log["paper_epochs"] = defaults_.paper_epochs;
  log["threads"] = o_.threads;
  log["views"] = views_;
  log["workers"] = o_.workers;
  log["prefetch"] = o_.prefetch;
  log["device"] = device_.str();
  log["validation_views"] = validator_->size();
  log["epoch_mean_loss"] = summary_.epoch_losses;
  json passes = json::array();
  for (const ValidationRecord& r : summary_.validations) {
    json p = {{"epoch", r.epoch}, {"global_step", r.step}, {"val_loss", r.loss}};
    for (const auto& [name, v] : r.loss_parts) p["val_" + name] = v;
    for (const auto& [name, v] : r.metrics) p[name] = std::isnan(v) ? json() : json(v);
    passes.push_back(p);
  }
  log["validation_passes"] = passes;
  log["seconds"] = start_time_.seconds();
  std::ofstream(out_ / "train_log.json") << log.dump(2) << "\n";
  if (!std::isnan(best_.value)) {
    summary_.best_checkpoint = (out_ / "best.pt").string();
    summary_.best_value = best_.value;
    summary_.best_epoch = best_.epoch;
  }
  if (o_.plot_script.empty()) return;
  const fs::path png = out_ / "loss_curve.png";
  const std::string cmd = fmt::format("/usr/bin/python3 '{}' '{}' '{}' > /dev/null 2>&1", o_.plot_script,
                                      (out_ / "train_log.csv").string(), png.string());
  if (std::system(cmd.c_str()) == 0 && fs::is_regular_file(png)) summary_.plot = png.string();
  else spdlog::warn("loss curve: {} failed (needs /usr/bin/python3 with matplotlib)", o_.plot_script);
}

}  // namespace phyir::model
