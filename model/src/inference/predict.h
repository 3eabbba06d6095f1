#pragma once
// The whole model on a batch of input images, as `phyir infer` and the validation pass run
// it: GMNet, GSNet's refinement (when asked), LNet and the rendering layer (when asked).
// Radiance comes out in input units (exposure.h). Private header (torch types).
#include <torch/torch.h>

#include "checkpoint.h"

namespace phyir::model {

struct ModelOutput {
  GMOutput maps;           // [B,C,Hi,Wi], refined by GSNet when it ran
  torch::Tensor probes;    // [B,Hr,Wr,h,w,3] linear radiance, input units (linear_probes: what the
                           // rendering layer used); undefined without LNet
  torch::Tensor rerender;  // [B,3,Hr,Wr] the rendering layer's image, input units
  double gmnet_ms = 0.0, gsnet_ms = 0.0, light_ms = 0.0;
};

// `image`: [B,3,Hi,Wi] sRGB-encoded in [0,1] at the configuration's input resolution.
// Call under a NoGradGuard with the networks in eval mode.
ModelOutput predict(Networks& nets, const ModelConfig& config, const torch::Tensor& image, bool use_gsnet,
                    bool use_light);

}  // namespace phyir::model
