#pragma once
// BatchNorm2d whose training statistics are the global batch's in data-parallel training: the
// per-channel sums of every rank's share are added up (batch_share.h), so N ranks normalise,
// and update the running statistics, as one process holding the whole batch. Outside a share
// (one process, eval mode, inference) it computes what torch's BatchNorm2d computes, with its
// parameters and buffers in its order and names, so checkpoints and encoder weights are
// unchanged. (Not a subclass: Debian's LibTorch does not export what a subclass links to.)
// Private header (torch types).
#include <torch/torch.h>

namespace phyir::model {

class SharedBatchNorm2dImpl : public torch::nn::Module {
 public:
  explicit SharedBatchNorm2dImpl(int64_t channels);
  torch::Tensor forward(const torch::Tensor& x);

  torch::Tensor weight, bias, running_mean, running_var, num_batches_tracked;

 private:
  torch::Tensor forward_shared(const torch::Tensor& x);
  double momentum_ = 0.1, eps_ = 1e-5;  // torch's defaults
};
TORCH_MODULE(SharedBatchNorm2d);

}  // namespace phyir::model
