#pragma once
// Data-parallel training's bookkeeping (docs/model-scale.md "Training on several processes"): which
// views of each global batch a rank reads, and the two collectives around the optimiser (the
// ranks start from rank 0's weights; gradients are averaged before each step). The losses' and
// BatchNorm's reductions over the global batch: batch_share.h. Private header (torch types).
#include <torch/torch.h>

#include <cstdint>
#include <vector>

namespace phyir::model {

class ProcessGroup;
struct Networks;

// A rank's views within one global batch of `views` views: rank r of `ranks` takes the
// contiguous slice [first, first + count), the first (views % ranks) ranks one view more.
struct RankSlice {
  int64_t first = 0, count = 0;
};
RankSlice rank_slice(int64_t views, int rank, int ranks);

// Optimiser steps per epoch for `views` views in global batches of `batch`. Every rank takes
// part in every step, so a last batch with fewer views than ranks is left out (that epoch has
// one step less than one process's; tell the user: trainer.cpp).
int64_t global_batches(int64_t views, int64_t batch, int ranks);

// The views of `order` (an epoch's) that `rank` reads, global batch after global batch, for
// the epoch's global_batches(). Its k-th batch of rank_batch() views (the last possibly short)
// is its slice of global batch k, as BatchStream cuts it.
std::vector<size_t> rank_order(const std::vector<size_t>& order, int64_t batch, int rank, int ranks);
int64_t rank_batch(int64_t batch, int rank, int ranks);

// Every rank gets rank 0's parameters and buffers (the same start whatever was loaded).
void broadcast_networks(ProcessGroup& group, Networks& nets);

// Each parameter's gradient becomes the mean over ranks (one collective for all of them).
void average_gradients(ProcessGroup& group, const std::vector<torch::Tensor>& params);

}  // namespace phyir::model
