// The stages of appendix B.1 and train(). The run itself: trainer.h; inference:
// inference.cpp; the rendering layer on ground truth: render_check.cpp.
#include "phyir/model/training.h"

#include <torch/torch.h>

#include <thread>

#include "phyir/core/error.h"
#include "phyir/core/setting_error.h"
#include "phyir/core/log.h"
#include "host_memory.h"
#include "trainer.h"

namespace phyir::model {

// --- Stages and defaults ----------------------------------------------------------------------

Stage parse_stage(const std::string& name) {
  if (name == "gmnet") return Stage::kGMNet;
  if (name == "lnet") return Stage::kLNet;
  if (name == "joint") return Stage::kJoint;
  if (name == "gsnet") return Stage::kGSNet;
  fail_setting("stage", "'{}': expected gmnet, lnet, joint or gsnet", name);
}

std::string stage_name(Stage s) {
  switch (s) {
    case Stage::kGMNet: return "gmnet";
    case Stage::kLNet: return "lnet";
    case Stage::kJoint: return "joint";
    case Stage::kGSNet: return "gsnet";
  }
  return "?";
}

StageDefaults stage_defaults(Stage s) {
  StageDefaults d{};
  switch (s) {
    case Stage::kGMNet:  // B.1: 120 epochs, lr 1e-4, batch 8, beta_B,R,M,D = 1, beta_N,gradient = 0.1
      d = {1e-4, 8, 120, {}};
      d.weights.probe = d.weights.coherence = d.weights.render = 0.0;
      break;
    case Stage::kLNet:  // 90 epochs, lr 1e-4, batch 4, beta_L,SC,render = 1
      d = {1e-4, 4, 90, {}};
      d.weights.base_color = d.weights.roughness = d.weights.metalness = d.weights.depth = 0.0;
      d.weights.normal = d.weights.gradient = 0.0;
      break;
    case Stage::kJoint:  // 10 epochs, lr 1e-5, batch 4, beta_L,render = 1, beta_SC = 0.1 (+ GMNet's losses)
      d = {1e-5, 4, 10, {}};
      d.weights.coherence = 0.1;
      break;
    case Stage::kGSNet:  // 80 epochs, lr 5e-4, batch 16, beta_B,R = 1, beta_N = 0.1
      d = {5e-4, 16, 80, {}};
      d.weights.metalness = d.weights.depth = d.weights.gradient = 0.0;
      d.weights.probe = d.weights.coherence = d.weights.render = 0.0;
      break;
  }
  return d;
}

void set_threads(int threads) {
  if (threads == 0) threads = int(std::thread::hardware_concurrency());
  torch::set_num_threads(std::max(1, threads));
}

TrainSummary train(const TrainOptions& options) {
  init_logging();
  set_threads(options.threads);
  retain_freed_memory();
  return Trainer(options).run();
}

}  // namespace phyir::model
