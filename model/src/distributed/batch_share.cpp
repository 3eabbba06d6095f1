// Reductions over the global batch of data-parallel training (batch_share.h).
#include "batch_share.h"

#include "phyir/core/error.h"
#include "process_group.h"

namespace phyir::model {

namespace {

struct Share {
  ProcessGroup* group = nullptr;
  int64_t first_view = 0;
};

// One share per thread: the training thread's (workers that read views never reduce).
thread_local Share current;

using torch::autograd::AutogradContext;
using torch::autograd::variable_list;

// y = sum over ranks of x; the adjoint sums the ranks' output gradients the same way.
struct RanksSum : torch::autograd::Function<RanksSum> {
  static torch::Tensor forward(AutogradContext*, const torch::Tensor& x) {
    torch::Tensor y = x.detach().clone().contiguous();
    current.group->sum(y, "a loss's batch sum");
    return y;
  }
  static variable_list backward(AutogradContext*, variable_list grad) {
    // The group can have left scope only after backward: the trainer's share spans both.
    if (!current.group) fail("batch_share: a shared sum's backward ran outside its BatchShare");
    torch::Tensor g = grad[0].contiguous().clone();
    current.group->sum(g, "a loss's batch sum (backward)");
    return {g};
  }
};

}  // namespace

BatchShare::BatchShare(ProcessGroup& group, int64_t first_view) {
  if (current.group) fail("batch_share: shares do not nest");
  current = {&group, first_view};
}

BatchShare::~BatchShare() { current = {}; }

torch::Tensor ranks_sum(const torch::Tensor& x) {
  if (!current.group) return x;
  // Gloo reduces at least one element: a 0-dim statistic travels as a 1-element vector.
  const torch::Tensor flat = x.reshape({-1});
  return RanksSum::apply(flat).reshape(x.sizes());
}

torch::Tensor batch_sum(const torch::Tensor& x) { return ranks_sum(x.sum()); }

torch::Tensor batch_max(const torch::Tensor& x) {
  torch::Tensor m = x.detach().max().reshape({1}).clone();
  if (current.group) current.group->max(m, "a loss's batch maximum");
  return m.reshape({});
}

bool batch_is_shared() { return current.group != nullptr; }

int64_t batch_first_view() { return current.first_view; }

}  // namespace phyir::model
