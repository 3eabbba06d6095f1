#pragma once
// A rank's batch as its share of the global batch. While a BatchShare is in scope (the trainer
// sets one around each step's forward and backward), the batch-wide reductions of the losses
// and of BatchNorm are taken over every rank's share, and the rendering layer numbers its pixels'
// random streams from the share's first view in the global batch. So N ranks, each with a share,
// compute the loss, gradients and BatchNorm statistics of one process holding the whole batch,
// whatever the shares' sizes (tests: ModelDistributed.*). Outside a share (one process,
// validation, inference) every function here is the plain single-process reduction.
// Private header (torch types).
#include <torch/torch.h>

#include <cstdint>

namespace phyir::model {

class ProcessGroup;

class BatchShare {
 public:
  // `first_view`: the share's first view's index within the global batch.
  BatchShare(ProcessGroup& group, int64_t first_view);
  ~BatchShare();
  BatchShare(const BatchShare&) = delete;
  BatchShare& operator=(const BatchShare&) = delete;
};

// x summed over the global batch: a 0-dim tensor, x.sum() of every rank's share added up.
// Differentiable: its backward sums the ranks' gradients, the adjoint of the sum, so each rank's
// parameter gradients are N times its share's part of the global loss's (the trainer averages
// them over ranks: process_group.h).
torch::Tensor batch_sum(const torch::Tensor& x);

// Elementwise sum over ranks of a per-share statistic (BatchNorm's per-channel sums), as
// batch_sum differentiable.
torch::Tensor ranks_sum(const torch::Tensor& x);

// The maximum of x over the global batch (not differentiable: detached).
torch::Tensor batch_max(const torch::Tensor& x);

// Whether a share is in scope (BatchNorm then uses the global batch's statistics).
bool batch_is_shared();

// The global index of this share's first view (0 outside a share).
int64_t batch_first_view();

}  // namespace phyir::model
