// The device setting: parsing, availability, tensor options (device.h).
#include "device.h"

#include "phyir/core/error.h"
#include "phyir/core/setting_error.h"

namespace phyir::model {

torch::Device parse_device(const std::string& value) {
  torch::optional<torch::Device> device;
  try {
    device = torch::Device(value);
  } catch (const std::exception&) {
    fail_setting("device", "'{}': expected cpu, cuda or cuda:N", value);
  }
  if (device->is_cpu()) {
    if (device->has_index() && device->index() != 0) fail_setting("device", "'{}': the CPU has no index but 0", value);
    return torch::kCPU;
  }
  if (!device->is_cuda()) fail_setting("device", "'{}': expected cpu, cuda or cuda:N", value);
  if (!torch::cuda::is_available())
    fail_setting("device",
                 "'{}': CUDA is not available to this LibTorch (it was built without CUDA, as Debian's is, or no "
                 "GPU is visible); use the cpu device, or build with a CUDA LibTorch (-DTorch_DIR=..., "
                 "docs/model-scale.md \"Build\")",
                 value);
  const int64_t gpus = static_cast<int64_t>(torch::cuda::device_count());
  if (device->has_index() && device->index() >= gpus)
    fail_setting("device", "'{}': this machine has {} CUDA device(s) (0 to {})", value, gpus, gpus - 1);
  return *device;
}

torch::TensorOptions float_options(const torch::Device& device) {
  return torch::TensorOptions().dtype(torch::kFloat).device(device);
}

}  // namespace phyir::model
