// Data-parallel bookkeeping: slices of the global batch and the collectives around the
// optimiser (data_parallel.h).
#include "data_parallel.h"

#include <algorithm>

#include "checkpoint.h"
#include "phyir/core/error.h"
#include "phyir/core/setting_error.h"
#include "process_group.h"

namespace phyir::model {

RankSlice rank_slice(int64_t views, int rank, int ranks) {
  const int64_t base = views / ranks, extra = views % ranks;
  return {rank * base + std::min<int64_t>(rank, extra), base + (rank < extra ? 1 : 0)};
}

int64_t global_batches(int64_t views, int64_t batch, int ranks) {
  if (batch < ranks)
    fail_setting("batch_size", "{} is smaller than the {} ranks (each rank needs a view of every batch)", batch, ranks);
  const int64_t full = views / batch, rest = views % batch;
  return full + (rest >= ranks ? 1 : 0);
}

int64_t rank_batch(int64_t batch, int rank, int ranks) { return rank_slice(batch, rank, ranks).count; }

std::vector<size_t> rank_order(const std::vector<size_t>& order, int64_t batch, int rank, int ranks) {
  const int64_t views = static_cast<int64_t>(order.size());
  std::vector<size_t> mine;
  for (int64_t k = 0, n = global_batches(views, batch, ranks); k < n; ++k) {
    const int64_t begin = k * batch;
    const RankSlice s = rank_slice(std::min(batch, views - begin), rank, ranks);
    mine.insert(mine.end(), order.begin() + begin + s.first, order.begin() + begin + s.first + s.count);
  }
  return mine;
}

namespace {

void broadcast_all(ProcessGroup& group, torch::nn::Module& net) {
  torch::NoGradGuard no_grad;
  for (torch::Tensor& p : net.parameters()) group.broadcast(p, 0, "the networks' parameters");
  for (torch::Tensor& b : net.buffers()) group.broadcast(b, 0, "the networks' buffers");
}

}  // namespace

void broadcast_networks(ProcessGroup& group, Networks& nets) {
  broadcast_all(group, *nets.gmnet);
  broadcast_all(group, *nets.lnet);
  broadcast_all(group, *nets.gsnet);
}

void average_gradients(ProcessGroup& group, const std::vector<torch::Tensor>& params) {
  std::vector<torch::Tensor> grads;
  for (const torch::Tensor& p : params)
    if (p.grad().defined()) grads.push_back(p.grad());
  if (grads.empty()) return;
  std::vector<torch::Tensor> flat;
  flat.reserve(grads.size());
  for (const torch::Tensor& g : grads) flat.push_back(g.reshape({-1}));
  torch::Tensor all = torch::cat(flat);
  group.sum(all, "the gradients");
  all.div_(group.size());
  int64_t offset = 0;
  for (torch::Tensor& g : grads) {
    g.copy_(all.narrow(0, offset, g.numel()).view_as(g));
    offset += g.numel();
  }
}

}  // namespace phyir::model
