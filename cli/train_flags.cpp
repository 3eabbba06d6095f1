// The flags of one training stage (train_flags.h).
#include "train_flags.h"

#ifdef PHYIR_HAVE_MODEL

#include <fmt/format.h>

#include "flag_registry.h"
#include "phyir/core/error.h"

namespace phyir::cli {

namespace {

// One value of appendix B.1 for each stage, "gmnet / lnet / joint / gsnet".
template <class Value>
std::string by_stage(Value value) {
  std::string text;
  for (model::Stage stage : {model::Stage::kGMNet, model::Stage::kLNet, model::Stage::kJoint, model::Stage::kGSNet})
    text += fmt::format("{}{}", text.empty() ? "" : " / ", value(model::stage_defaults(stage)));
  return text;
}

// The loss weights, augmentation, validation and learning-rate schedule, each an option group.
void add_train_group_flags(CLI::App* cmd, TrainFlags& f) {
  model::TrainOptions& o = f.options;
  auto* wopt = cmd->add_option_group("loss weights", "override every weight of the stage (defaults: B.1)");
  wopt->add_option("--w-basecolor", f.weights.base_color, "beta_B");
  wopt->add_option("--w-roughness", f.weights.roughness, "beta_R");
  wopt->add_option("--w-metalness", f.weights.metalness, "beta_M");
  wopt->add_option("--w-depth", f.weights.depth, "beta_D");
  wopt->add_option("--w-normal", f.weights.normal, "beta_N");
  wopt->add_option("--w-gradient", f.weights.gradient, "beta_gradient");
  wopt->add_option("--w-probe", f.weights.probe, "beta_L");
  wopt->add_option("--w-coherence", f.weights.coherence, "beta_SC");
  wopt->add_option("--w-render", f.weights.render, "beta_render");
  cmd->add_option("--probe-loss-weight", o.probe_loss_weight,
                  "none, or stderr: weight each probe texel's loss term by its ground truth's standard error "
                  "(probe_stderr.exr; docs/model.md \"Probe loss weighting\")")
      ->check(CLI::IsMember({"none", "stderr"}))
      ->capture_default_str();
  auto* aug = cmd->add_option_group("augmentation", "training only, drawn per (seed, epoch, view); docs/model.md");
  aug->add_flag("!--no-augment", o.augment.enabled, "no yaw rotation, mirroring or exposure jitter");
  aug->add_flag("!--no-rotate", o.augment.rotate, "no yaw rotation");
  aug->add_flag("!--no-mirror", o.augment.mirror, "no horizontal mirroring");
  const model::AugmentOptions augment;
  aug->add_option("--exposure-jitter", f.jitter,
                  fmt::format("LO,HI: exposure jitter U[LO, HI) stops on input and targets (default {},{}; 0,0 = none)",
                              augment.exposure_min_stops, augment.exposure_max_stops))
      ->delimiter(',')
      ->expected(2);
  auto* val = cmd->add_option_group("validation", "every N epochs on the dataset's validation split");
  val->add_option("--val-split", o.validation.split, "split to validate on (\"\" = none)")->capture_default_str();
  val->add_option("--val-every", o.validation.every, "epochs between validation passes (0 = none)")->capture_default_str();
  val->add_option("--val-views", o.validation.max_views, "validate on the first N views of the split (0 = all)")
      ->capture_default_str();
  val->add_option("--best-metric", o.validation.best_metric,
                  "keep best.pt by val_loss or a phyir eval metric (normal_deg, basecolor_mse, depth_abs_rel, "
                  "probe_ssim, rerender_mse, ...)")->capture_default_str();
  auto* sched = cmd->add_option_group("learning-rate schedule", "the rate of every step from the base rate (--lr)");
  sched->add_option("--lr-schedule", o.schedule.kind, "constant (the paper's), step or cosine (default constant; "
                    "a resumed run keeps its checkpoint's)");
  sched->add_option("--lr-step-epochs", o.schedule.step_epochs, "step: multiply by --lr-gamma every N epochs "
                    "(default a third of --epochs)");
  sched->add_option("--lr-gamma", o.schedule.gamma, "step: the factor")->capture_default_str();
  sched->add_option("--lr-min-fraction", o.schedule.min_fraction, "cosine: the last step's rate / the base rate")
      ->capture_default_str();
}

// The names the model gives the settings it checks (TrainOptions, phyir/model/training.h).
void record_train_settings(CLI::App* cmd) {
  const std::pair<const char*, const char*> settings[] = {
      {"data_dir", "--data"},          {"out_dir", "--out"},
      {"stage", "--stage"},            {"split", "--split"},
      {"init", "--init"},              {"resume", "--resume"},
      {"epochs", "--epochs"},          {"learning_rate", "--lr"},
      {"batch_size", "--batch"},       {"seed", "--seed"},
      {"threads", "--threads"},        {"workers", "--workers"},
      {"prefetch", "--prefetch"},      {"device", "--device"},
      {"max_steps", "--max-steps"},    {"checkpoint_every", "--checkpoint-every"},
      {"max_views", "--max-views"},    {"encoder_weights", "--encoder-weights"},
      {"target_units", "--target-units"}, {"probe_loss_weight", "--probe-loss-weight"}, {"augment.exposure_min_stops", "--exposure-jitter"},
      {"validation.split", "--val-split"}, {"validation.every", "--val-every"},
      {"validation.max_views", "--val-views"}, {"validation.best_metric", "--best-metric"},
      {"schedule.kind", "--lr-schedule"}, {"schedule.step_epochs", "--lr-step-epochs"},
      {"schedule.gamma", "--lr-gamma"}, {"schedule.min_fraction", "--lr-min-fraction"}};
  for (const auto& [setting, flag] : settings) sets(cmd, setting, flag);
}

}  // namespace

void add_train_flags(CLI::App* cmd, TrainFlags& f) {
  f.cmd = cmd;
  model::TrainOptions& o = f.options;
  model::ModelConfig& c = o.config;
  // Required, checked by finish(): `phyir train slurm` has them only after its --.
  cmd->add_option("--data", o.data_dir, "dataset folder (view folders with color.exr, input.png, AOVs, probes); required")
      ->check(CLI::ExistingDirectory);
  cmd->add_option("--out", o.out_dir, "output folder (checkpoints, logs, loss curve); required");
  cmd->add_option("--stage", f.stage, "gmnet | lnet | joint | gsnet (paper appendix B.1)")->capture_default_str();
  cmd->add_option("--split", o.split, "with a manifest.json: the split to train on (train, val, test; \"\" = all)")
      ->capture_default_str();
  cmd->add_option("--init", o.init, "checkpoint of the previous stage to start from");
  cmd->add_flag("--resume", o.resume, "continue --out/checkpoint.pt exactly where it stopped");
  cmd->add_option("--epochs", o.epochs,
                  "epochs to reach (paper: " + by_stage([](const model::StageDefaults& d) { return d.paper_epochs; }) + ")")
      ->capture_default_str();
  cmd->add_option("--lr", o.learning_rate,
                  "Adam learning rate (default: " +
                      by_stage([](const model::StageDefaults& d) { return d.learning_rate; }) + " by stage)");
  cmd->add_option("--batch", o.batch_size,
                  "batch size (default: " + by_stage([](const model::StageDefaults& d) { return d.batch_size; }) +
                      " by stage)");
  cmd->add_option("--seed", o.seed, "random seed (initialisation, shuffling, Monte-Carlo samples)")->capture_default_str();
  cmd->add_option("--threads", o.threads, "torch threads (1 = bit-reproducible runs)")->capture_default_str();
  cmd->add_option("--workers", o.workers,
                  "threads reading and augmenting the next batches while a step runs (0 = read each batch when "
                  "due); results do not depend on it")
      ->check(CLI::NonNegativeNumber)->capture_default_str();
  cmd->add_option("--prefetch", o.prefetch,
                  "batches read ahead with --workers: at most batch x (prefetch + 1) views in memory, whatever "
                  "the dataset's size")
      ->check(CLI::PositiveNumber)->capture_default_str();
  cmd->add_option("--device", o.device, "cpu, cuda or cuda:N (CUDA needs a CUDA LibTorch: docs/model-scale.md \"Build\")")
      ->capture_default_str();
  cmd->add_option("--max-steps", o.max_steps, "stop after this many steps in total (0 = all epochs)");
  cmd->add_option("--checkpoint-every", o.checkpoint_every, "also checkpoint every N steps (0 = per epoch)");
  cmd->add_option("--max-views", o.max_views, "use only the first N views (0 = all)");
  cmd->add_option("--encoder-weights", o.encoder_weights, "ResNet-18 encoder weights (torch::save of the encoder)");
  cmd->add_option("--input-height", c.input_height, "GMNet input height (multiple of 32; paper 256)")->capture_default_str();
  cmd->add_option("--input-width", c.input_width, "GMNet input width (multiple of 32; paper 512)")->capture_default_str();
  cmd->add_option("--render-height", c.render_height, "LNet / rendering height (multiple of 16; paper 128)")->capture_default_str();
  cmd->add_option("--render-width", c.render_width, "LNet / rendering width (multiple of 16; paper 256)")->capture_default_str();
  cmd->add_option("--probe-height", c.probe_height, "probe height (paper 16)")->capture_default_str();
  cmd->add_option("--probe-width", c.probe_width, "probe width (paper 32)")->capture_default_str();
  cmd->add_option("--diffuse-samples", c.diffuse_samples, "rendering layer diffuse samples (paper 512)")->capture_default_str();
  cmd->add_option("--specular-samples", c.specular_samples, "rendering layer specular samples (paper 256)")->capture_default_str();
  cmd->add_option("--width-divisor", c.width_divisor, "divide every channel count by 2 or 4 (quick experiments; 1 = the paper)")->capture_default_str();
  cmd->add_option("--lnet-head", c.lnet_head, "LNet's last two layers: paper (A.2, 3x3 to h*w*3) or light (1x1; docs/model.md)")->capture_default_str();
  cmd->add_option("--target-units", o.target_units,
                  "study switch: LNet's probe and re-render targets in input units (x 2^exposure_stops, the "
                  "default) or absolute (as before the exposure fix); overrides --init's")
      ->check(CLI::IsMember({"input", "absolute"}));
  add_train_group_flags(cmd, f);
  cmd->add_flag("--quiet", f.quiet, "no per-step progress lines");
  record_train_settings(cmd);
}

void TrainFlags::finish() {
  if (options.data_dir.empty()) fail("--data: a dataset folder is required");
  if (options.out_dir.empty()) fail("--out: an output folder is required");
  options.stage = model::parse_stage(stage);
  if (jitter.size() == 2) {
    options.augment.exposure_min_stops = jitter[0];
    options.augment.exposure_max_stops = jitter[1];
  }
  options.progress = !quiet;
  bool any_weight = false;
  for (const char* name : {"--w-basecolor", "--w-roughness", "--w-metalness", "--w-depth", "--w-normal",
                           "--w-gradient", "--w-probe", "--w-coherence", "--w-render"})
    any_weight = any_weight || cmd->count(name) > 0;
  if (any_weight) {
    // Unset weights keep the stage's defaults.
    model::LossWeights merged = model::stage_defaults(options.stage).weights;
    if (cmd->count("--w-basecolor")) merged.base_color = weights.base_color;
    if (cmd->count("--w-roughness")) merged.roughness = weights.roughness;
    if (cmd->count("--w-metalness")) merged.metalness = weights.metalness;
    if (cmd->count("--w-depth")) merged.depth = weights.depth;
    if (cmd->count("--w-normal")) merged.normal = weights.normal;
    if (cmd->count("--w-gradient")) merged.gradient = weights.gradient;
    if (cmd->count("--w-probe")) merged.probe = weights.probe;
    if (cmd->count("--w-coherence")) merged.coherence = weights.coherence;
    if (cmd->count("--w-render")) merged.render = weights.render;
    options.custom_weights = true;
    options.weights = merged;
  }
  options.plot_script = std::string(PHYIR_SOURCE_ROOT) + "/scripts/plot_training.py";
}

}  // namespace phyir::cli

#endif
