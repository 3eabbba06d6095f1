#pragma once
// The device a run computes on (the "device" setting, docs/model-scale.md "Build"): parsed once, checked
// against what this LibTorch was built with, and the tensor options every tensor a run makes
// from nothing is created with. Data is decoded into host memory and each batch moved once
// (Batch::to); the networks and the optimiser's state live on the device. Private header.
#include <torch/torch.h>

#include <string>

namespace phyir::model {

// `value` in torch::Device's syntax restricted to cpu, cuda, cuda:N. Throws phyir::SettingError
// ("device") naming the value when it does not parse, names another kind of device, or names one
// this LibTorch cannot use (CUDA on a CPU-only build such as Debian's, an index past the
// GPUs present).
torch::Device parse_device(const std::string& value);

// float32 on `device`: the options of every tensor a run creates without a tensor to copy
// them from (x.options() is used when there is one).
torch::TensorOptions float_options(const torch::Device& device);

}  // namespace phyir::model
