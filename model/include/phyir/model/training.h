#pragma once
// The torch-free public API of phyir_model: training stages and inference as plain structs
// and functions, so the CLI (and anything else) compiles without LibTorch's headers.
// Network, rendering layer and losses: model/src (private, torch types). Docs: docs/model.md.
#include <cstdint>
#include <limits>
#include <string>
#include <utility>
#include <vector>

namespace phyir::model {

// The four stages of the paper's appendix B.1.
enum class Stage { kGMNet, kLNet, kJoint, kGSNet };
Stage parse_stage(const std::string& name);  // gmnet | lnet | joint | gsnet; else SettingError "stage"
std::string stage_name(Stage stage);

// Resolutions and sample counts. Paper: input 256x512, rendering 128x256, probes 16x32,
// 512 diffuse / 256 specular samples. Defaults are smaller so CPU training is practical: the
// labels keep the renderer's (and the paper's) 16x32 probes (view::ProbeLayout), the network
// predicts 8x16 (LNet's last layer has h*w*3 channels, 4x fewer), and load_view resamples each
// label onto the network's grid and texels (nearest probe, area-averaged texels).
struct ModelConfig {
  int input_height = 128, input_width = 256;   // GMNet / GSNet input (multiples of 32)
  int render_height = 32, render_width = 64;   // LNet output grid and rendering layer (multiples of 16)
  int probe_height = 8, probe_width = 16;      // per-pixel probe size
  int diffuse_samples = 64, specular_samples = 32;
  int guided_radius = 2;                       // GSNet's guided filter radius (paper: 2)
  int width_divisor = 1;                       // divides every channel count: 1 = the paper's
                                               // networks; 2 or 4 for quick experiments and tests
  std::string lnet_head = "paper";             // paper (A.2) or light: LNet's last two layers
                                               // i128-o128 k3, i128-o(h*w*3) k1 (docs/model.md)
  std::string target_units = "input";          // the probe and re-render targets' unit: input
                                               // (x 2^exposure_stops, the default) or absolute
                                               // (the study's no-exposure-fix arm; docs/model.md)
};

// Loss weights (the betas of eqs. 5 and 12).
struct LossWeights {
  double base_color = 1.0, roughness = 1.0, metalness = 1.0, depth = 1.0;
  double normal = 0.1, gradient = 0.1;
  double probe = 1.0, coherence = 1.0, render = 1.0;
  // The probe loss's texels weighted by their ground truth's standard error (probe_stderr.exr;
  // docs/model.md "Probe loss weighting"); set from TrainOptions::probe_loss_weight.
  bool probe_stderr = false;
};

// Appendix B.1's learning rate, batch size, epochs and loss weights for a stage.
struct StageDefaults {
  double learning_rate;
  int batch_size;
  int paper_epochs;
  LossWeights weights;
};
StageDefaults stage_defaults(Stage stage);

// Training-time augmentation (model/src/data/augment.h, docs/model.md "Augmentation"). Each draw
// depends only on (seed, epoch, view), so runs are reproducible and resumable.
struct AugmentOptions {
  bool enabled = true;     // off: every view as loaded (validation and evaluation never augment)
  bool rotate = true;      // yaw: a circular shift of the panorama by a multiple of 1/gcd(widths)
  bool mirror = true;      // horizontal flip (x -> -x), with probability 1/2
  double exposure_min_stops = -1.0;  // exposure jitter U[min, max) stops on input and targets
  double exposure_max_stops = 0.5;   // (equal: no jitter)
};

// Validation on the dataset's `split` every `every` epochs (model/src/training/validation.h).
struct ValidationOptions {
  std::string split = "val";   // empty, or a dataset without this split: no validation
  int every = 1;               // epochs between passes (0: never)
  int max_views = 16;          // the first N views of the split (0: all)
  std::string best_metric = "val_loss";  // val_loss or a `phyir eval` metric (docs/model.md)
};

// The learning rate over the run (model/src/training/lr_schedule.h). The base rate is TrainOptions'.
struct LrScheduleOptions {
  std::string kind;          // constant (the paper's), step or cosine; empty: constant, or
                             // the checkpoint's when resuming
  int step_epochs = 0;       // step: multiply by gamma every N epochs (0: a third of the epochs)
  double gamma = 0.1;        // step
  double min_fraction = 0.01;  // cosine: the last step's rate over the base rate
};

// Data-parallel training (docs/model-scale.md "Training on several processes"): this process is rank
// `rank` of `world_size`, and the ranks meet at `rendezvous`: file:PATH (a file on a file
// system every rank sees; it must not exist before the run) or tcp:HOST:PORT (a store that
// rank 0 serves on HOST). `phyir train`'s local processes and `phyir train slurm`'s script fill
// these in. The batch size stays the global batch: N ranks at batch B train as one process at
// batch B.
struct DistributedOptions {
  int rank = 0;
  int world_size = 1;          // 1: one process, no group
  std::string rendezvous;
  int timeout_seconds = 1800;  // how long a rank waits for the others in a collective (rank 0's
                               // validation passes and checkpoints included) before it fails
};

struct TrainOptions {
  std::string data_dir;     // a dataset (manifest.json, docs/dataset.md) or a folder of view folders
  std::string split = "train";  // the manifest's split to train on (empty: every view)
  std::string out_dir;      // checkpoint.pt, best.pt, train_log.csv/json, val_log.csv, loss_curve.png
  Stage stage = Stage::kGMNet;
  ModelConfig config;       // ignored when `init` or `resume` gives one (the checkpoint's wins)
  int epochs = 1;
  double learning_rate = 0.0;  // 0: the stage's default
  int batch_size = 0;          // 0: the stage's default
  bool custom_weights = false; // false: the stage's default weights
  LossWeights weights;
  uint64_t seed = 1;
  int threads = 1;             // torch intra-op threads (set explicitly; torch's default is 1 here)
  int workers = 2;             // threads reading and augmenting batches ahead (0: on the training thread)
  int prefetch = 2;            // batches read ahead with workers: at most batch x (prefetch + 1) views
                               // in memory (docs/model-scale.md "Streaming"); results do not
                               // depend on either
  std::string device = "cpu";  // cpu, cuda or cuda:N (torch::Device; CUDA needs a CUDA LibTorch)
  std::string init;            // checkpoint whose networks this stage starts from (earlier stage)
  std::string encoder_weights; // optional ResNet-18 encoder weights (torch::save of the encoder)
  bool resume = false;         // continue out_dir/checkpoint.pt exactly where it stopped
  int64_t max_steps = 0;       // stop after this many optimiser steps in total (0: run all epochs)
  int64_t checkpoint_every = 0;  // also checkpoint every N steps (0: at the end of each epoch only)
  int max_views = 0;           // use only the first N views (0: all)
  std::string target_units;    // input | absolute: overrides the `init` checkpoint's (a study switch,
                               // docs/model.md "Exposure and units"); empty: the checkpoint's, else input
  std::string probe_loss_weight = "none";  // none | stderr: weight the probe loss's texels by their
                                           // ground truth's standard error (docs/model.md)
  bool progress = true;        // one line per step with live loss values
  std::string plot_script;     // scripts/plot_training.py; empty: no loss-curve PNG
  AugmentOptions augment;
  ValidationOptions validation;
  LrScheduleOptions schedule;
  DistributedOptions distributed;
};

// One validation pass: the stage's loss on the validation views and `phyir eval`'s metrics
// (NaN where the stage's networks do not predict them).
struct ValidationRecord {
  int epoch = 0;               // epochs done when it ran
  int64_t step = 0;            // optimiser steps done when it ran
  double loss = 0.0;                                        // the stage's weighted loss
  std::vector<std::pair<std::string, double>> loss_parts;   // its components, unweighted
  std::vector<std::pair<std::string, double>> metrics;      // `phyir eval`'s, absolute radiance
};

struct TrainSummary {
  int64_t steps = 0;           // optimiser steps done in total (including before a resume)
  int epochs_done = 0;
  double first_loss = 0.0;     // mean loss of the first epoch run in this call
  double last_loss = 0.0;      // mean loss of the last epoch run in this call
  std::vector<double> epoch_losses;  // mean loss per epoch run in this call
  std::string checkpoint;
  std::string plot;            // loss-curve PNG, empty if not written
  std::vector<ValidationRecord> validations;  // the passes run in this call
  std::string best_checkpoint; // best.pt, empty when no validation ran
  double best_value = 0.0;     // of options.validation.best_metric
  int best_epoch = 0;
};

// Runs one stage. Throws phyir::Error on bad data, bad options, or a non-finite loss (the
// message names the step and the loss components; the last checkpoint stays valid).
TrainSummary train(const TrainOptions& options);

struct InferOptions {
  std::string checkpoint;
  std::string input;        // panorama .png (LDR, as input.png) or .exr/.hdr (HDR: exposed, then sRGB)
  std::string out_dir;
  int threads = 0;          // torch threads; 0: every core (outputs are the same for any count)
  std::string device = "cpu";  // cpu, cuda or cuda:N (as TrainOptions::device)
  uint64_t seed = 1;        // the rendering layer's Monte-Carlo samples
  // The input's exposure in stops (input = display(2^stops x radiance)). NaN: for an HDR
  // input the dataset's auto exposure; for a .png its folder's view.json, else unknown.
  double exposure = std::numeric_limits<double>::quiet_NaN();
  bool absolute = true;     // probes and re-render in absolute radiance when the exposure is
                            // known; false (or unknown exposure): in the input's relative units
};

// Writes depth.exr, normal.exr, basecolor.exr, roughness.exr, metalness.exr (input
// resolution), probes.exr (mosaic), probe_mask.exr, rerender.exr (rendering resolution),
// input.png and infer.json (with the radiance unit), in the renderer's conventions.
void infer(const InferOptions& options);

// The rendering layer on ground truth: a view folder's own maps and probes (probes.exr,
// probe_mask.exr from `phyir render` with probes) re-rendered and compared with its color.exr,
// at the probe grid's resolution (maps area-resized to it) over the pixels that see an opaque,
// non-emissive surface with a valid probe.
struct RenderCheckOptions {
  std::string view_dir;
  std::string out_dir;        // rerender.exr, rerender_diffuse.exr, rerender_specular.exr, check.json; empty: none
  int diffuse_samples = 512;  // the paper's counts
  int specular_samples = 256;
  uint64_t seed = 1;
  int threads = 1;
};
struct RenderCheckResult {
  int width = 0, height = 0;  // the probe grid (= rendering resolution)
  int64_t pixels = 0;         // pixels compared
  double mse = 0.0;           // mean over pixels and channels of (I - I~)^2
  double relative_mse = 0.0;  // sum (I - I~)^2 / sum I^2
  double mean_color = 0.0;    // mean of I over the compared pixels and channels
  double mean_abs_error = 0.0;
  double mean_rerender = 0.0; // mean of I~ (bias check: compare with mean_color)
};
RenderCheckResult check_render_layer(const RenderCheckOptions& options);

// Sets torch's intra-op thread count (commands call it before any work); 0: every core.
void set_threads(int threads);

}  // namespace phyir::model
