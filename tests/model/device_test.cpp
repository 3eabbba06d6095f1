// The device setting (model/src/networks/device.h): cpu parses to the CPU, anything else is refused
// naming the setting and the value; CUDA on a LibTorch without it (Debian's) is refused with the fix; the options
// helper makes float32 tensors on the device; a batch moved to the CPU is the batch itself.
#include "data.h"
#include "device.h"
#include "phyir/core/error.h"

namespace pm = phyir::model;

namespace {

std::string error_of(const std::string& value) {
  try {
    pm::parse_device(value);
  } catch (const phyir::Error& e) {
    return e.what();
  }
  return {};
}

}  // namespace

TEST(ModelDevice, CpuParsesAndOtherDevicesAreNamedInTheError) {
  EXPECT_EQ(pm::parse_device("cpu"), torch::Device(torch::kCPU));
  EXPECT_EQ(pm::parse_device("cpu:0"), torch::Device(torch::kCPU));
  for (const std::string bad : {"gpu", "", "cuda:x", "mps", "cpu:1"}) {
    const std::string message = error_of(bad);
    EXPECT_NE(message.find("device: '" + bad + "'"), std::string::npos) << bad << ": " << message;
  }
  if (torch::cuda::is_available()) GTEST_SKIP() << "this LibTorch has CUDA: the unavailable-device error is not reachable";
  for (const std::string cuda : {"cuda", "cuda:0", "cuda:1"}) {
    const std::string message = error_of(cuda);
    EXPECT_NE(message.find("device: '" + cuda + "': CUDA is not available"), std::string::npos) << message;
    EXPECT_NE(message.find("use the cpu device"), std::string::npos) << message;
  }
}

TEST(ModelDevice, OptionsHelperAndBatchMove) {
  const torch::TensorOptions o = pm::float_options(pm::parse_device("cpu"));
  EXPECT_EQ(o.dtype(), torch::kFloat);
  EXPECT_EQ(o.device(), torch::Device(torch::kCPU));
  pm::ViewTensors v;
  v.image = torch::rand({3, 4, 8}, o);
  v.depth = torch::rand({1, 4, 8}, o);
  const pm::Batch b = pm::collate({v, v});
  const pm::Batch moved = b.to(torch::kCPU);
  EXPECT_TRUE(moved.image.is_same(b.image));  // no copy on the CPU
  EXPECT_FALSE(moved.probes.defined());
  EXPECT_EQ(moved.index.device(), torch::Device(torch::kCPU));
}
