#pragma once
// One forward pass of a stage and its weighted losses (sec. 3.2, B.1), shared by the
// training step and the validation pass. Private header (torch types).
#include <torch/torch.h>

#include <string>
#include <utility>
#include <vector>

#include "checkpoint.h"
#include "data.h"
#include "render_layer.h"

namespace phyir::model {

// Which networks a stage trains; the others are frozen (eval mode, no gradients).
struct StageNetworks {
  bool gmnet = false, lnet = false, gsnet = false;
  static StageNetworks of(Stage stage);
};

// Named loss components of one step (unweighted values, detached) and the weighted total.
struct StepLoss {
  torch::Tensor total;
  std::vector<std::pair<std::string, torch::Tensor>> parts;
  void add(const std::string& name, double weight, const torch::Tensor& value);
};
std::string format_parts(const StepLoss& loss);  // "basecolor 0.012, depth 0.3"

struct LightResult {
  torch::Tensor log_probes;  // [B,Hr,Wr,h,w,3], log(1 + L)
  torch::Tensor probes;      // [B,Hr,Wr,h,w,3], linear_probes(log_probes): what was rendered
  RenderOutput render;
};

// Linear radiance from LNet's log(1 + L): expm1 of it clamped at 30 (L <= 1.1e13, no
// overflow), computed in place of the clamp's result (one large tensor fewer).
torch::Tensor linear_probes(const torch::Tensor& log_probes);

// LNet on the image and GMNet's maps, then the rendering layer on its probes (the maps
// area-resized to the rendering resolution).
LightResult run_light(Networks& nets, const ModelConfig& config, const torch::Tensor& image, const GMOutput& gm);

// The stage's forward pass on a batch and its losses. GMNet runs without gradients when the
// stage does not train it. Fails when every weight is 0 or the stage needs probes it lacks.
StepLoss stage_loss(Networks& nets, const ModelConfig& config, const LossWeights& weights, StageNetworks train,
                    const Batch& batch);

}  // namespace phyir::model
