// BatchNorm over the global batch of data-parallel training (shared_batch_norm.h).
#include "shared_batch_norm.h"

#include "batch_share.h"
#include "phyir/core/error.h"

namespace phyir::model {

SharedBatchNorm2dImpl::SharedBatchNorm2dImpl(int64_t channels) {
  weight = register_parameter("weight", torch::ones({channels}));
  bias = register_parameter("bias", torch::zeros({channels}));
  running_mean = register_buffer("running_mean", torch::zeros({channels}));
  running_var = register_buffer("running_var", torch::ones({channels}));
  num_batches_tracked = register_buffer("num_batches_tracked", torch::tensor(0, torch::dtype(torch::kLong)));
}

torch::Tensor SharedBatchNorm2dImpl::forward(const torch::Tensor& x) {
  if (x.dim() != 4) fail("SharedBatchNorm2d: expected a 4-D input, got {}-D", x.dim());
  if (is_training() && batch_is_shared()) return forward_shared(x);
  // As torch::nn::BatchNorm2d (momentum 0.1).
  if (is_training()) num_batches_tracked.add_(1);
  return torch::batch_norm(x, weight, bias, running_mean, running_var, is_training(), momentum_, eps_,
                           at::globalContext().userEnabledCuDNN());
}

torch::Tensor SharedBatchNorm2dImpl::forward_shared(const torch::Tensor& x) {
  const int64_t C = x.size(1);
  const std::vector<int64_t> reduce = {0, 2, 3};
  auto channels = [C](const torch::Tensor& t) { return t.view({1, C, 1, 1}); };
  // Two passes, as torch's BatchNorm: the mean first, then the variance about it (E[x^2] -
  // mean^2 loses digits when activations are large).
  const torch::Tensor count = torch::full({1}, static_cast<double>(x.numel() / C), x.options());
  const torch::Tensor first = ranks_sum(torch::cat({x.sum(reduce), count}));
  const torch::Tensor n = first[C];
  const torch::Tensor mean = first.narrow(0, 0, C) / n;
  const torch::Tensor centred = x - channels(mean);
  const torch::Tensor var = ranks_sum(centred.square().sum(reduce)) / n;  // biased, as torch normalises
  {
    torch::NoGradGuard no_grad;
    const double m = momentum_;
    running_mean.mul_(1.0 - m).add_(mean.detach(), m);
    running_var.mul_(1.0 - m).add_(var.detach() * n / (n - 1.0).clamp_min(1.0), m);  // unbiased, as torch keeps
    num_batches_tracked.add_(1);
  }
  return centred * channels(torch::rsqrt(var + eps_)) * channels(weight) + channels(bias);
}

}  // namespace phyir::model
