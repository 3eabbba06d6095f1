#pragma once
// The networks of PhyIR (paper sec. 3.2 and appendix A): GMNet, LNet, GSNet.
// Private header (torch types): used by model/src and tests/model only.
//
// Layout conventions of every tensor here:
//   images and maps  [B, C, H, W], row 0 = +Y up, centre column = -Z (docs/conventions.md);
//   per-pixel probes [B, H, W, h, w, 3], probe (i, j) is a world-oriented h x w equirect block;
//   probe mosaics    [B, 3, H*h, W*w] (the probes.exr layout).
#include <torch/torch.h>

#include <string>

#include "shared_batch_norm.h"

namespace phyir::model {

// Whether CirConv calls oneDNN itself: without a gradient, for float on the CPU, when LibTorch
// has oneDNN (inference and validation; docs/performance.md, "Inference"). Training keeps
// ATen's choice of backend.
bool convolve_with_onednn(const torch::Tensor& x);

// F::normalize along the channels of [B,C,H,W] maps: x / max(|x|, eps). Without a gradient it
// sums the squares itself, because ATen's norm over the channels of an NCHW tensor is about
// 70x slower (31 ms against 0.4 ms for a 3x256x512 map on 2 threads); the two agree to float
// rounding. With a gradient it is F::normalize, so training is unchanged.
torch::Tensor normalize_channels(const torch::Tensor& x, double eps = 1e-6);

// CirP (circular padding, Wang et al. / UniFuse): wrap along the panorama's width,
// replicate along its height (the poles have no neighbour beyond them).
torch::Tensor cirpad(const torch::Tensor& x, int pad_h, int pad_w);

// A k x k convolution preceded by CirP, so the output keeps H / stride x W / stride.
struct CirConvImpl : torch::nn::Module {
  CirConvImpl(int in, int out, int kernel, int stride = 1, bool bias = true);
  torch::Tensor forward(const torch::Tensor& x);
  // Without a gradient only (convolve_with_onednn): output channel o is the layer's channel
  // order[o]; the output has x's memory format (channels-last in, channels-last out).
  torch::Tensor forward_reordered(const torch::Tensor& x, const torch::Tensor& order);
  int pad_lo = 0, pad_hi = 0;
  torch::nn::Conv2d conv{nullptr};

 private:
  torch::Tensor onednn_forward(const torch::Tensor& padded, const torch::Tensor& weight,
                               const torch::Tensor& bias) const;
};
TORCH_MODULE(CirConv);

// --- GMNet (appendix A.1) ------------------------------------------------------------------

struct BasicBlockImpl : torch::nn::Module {
  BasicBlockImpl(int in, int out, int stride);
  torch::Tensor forward(const torch::Tensor& x);
  CirConv conv1{nullptr}, conv2{nullptr};
  SharedBatchNorm2d bn1{nullptr}, bn2{nullptr};
  torch::nn::Conv2d down{nullptr};
  SharedBatchNorm2d down_bn{nullptr};
};
TORCH_MODULE(BasicBlock);

// ResNet-18 (He et al. 2016) with CirP. Returns the skip features at 1/2, 1/4, 1/8, 1/16
// and the bottleneck at 1/32 (64, 64, 128, 256, 512 channels).
// `div` divides every channel count (1: the paper's network; tests use 4 to be quick).
struct ResNet18EncoderImpl : torch::nn::Module {
  explicit ResNet18EncoderImpl(int div = 1);
  std::vector<torch::Tensor> forward(const torch::Tensor& x);
  CirConv conv1{nullptr};
  SharedBatchNorm2d bn1{nullptr};
  torch::nn::Sequential layer1{nullptr}, layer2{nullptr}, layer3{nullptr}, layer4{nullptr};
};
TORCH_MODULE(ResNet18Encoder);

// One decoder branch of A.1: 11 convolutions, ELU after each but the output layer.
//   i512-o256 | up, cat skip(256): i512-o256, i256-o128 | up, cat(128): i256-o128, i128-o64 |
//   up, cat(64): i128-o64, i64-o32 | up, cat(64): i96-o32, i32-o16 | up: i16-o16, i16-o{3,1}
struct DecoderImpl : torch::nn::Module {
  DecoderImpl(int out_channels, int div = 1);
  torch::Tensor forward(const std::vector<torch::Tensor>& features);
  torch::nn::ModuleList convs{nullptr};
};
TORCH_MODULE(Decoder);

struct GMOutput {
  torch::Tensor depth;       // [B,1,H,W] metres, > 0 (softplus)
  torch::Tensor normal;      // [B,3,H,W] unit, world space
  torch::Tensor base_color;  // [B,3,H,W] in [0,1] (sigmoid)
  torch::Tensor roughness;   // [B,1,H,W] in [0,1]
  torch::Tensor metalness;   // [B,1,H,W] in [0,1]
};

struct GMNetImpl : torch::nn::Module {
  explicit GMNetImpl(int div = 1);
  // image: [B,3,H,W] LDR in [0,1], H and W multiples of 32.
  GMOutput forward(const torch::Tensor& image);
  // Loads encoder weights saved with torch::save(encoder) (e.g. a converted ImageNet ResNet-18).
  void load_encoder(const std::string& path);
  ResNet18Encoder encoder{nullptr};
  Decoder depth{nullptr}, normal{nullptr}, base_color{nullptr}, roughness{nullptr}, metalness{nullptr};
};
TORCH_MODULE(GMNet);

// --- LNet (appendix A.2) -------------------------------------------------------------------

// Convolution (CirP) + GroupNorm with 16-channel groups + ReLU.
struct ConvGNImpl : torch::nn::Module {
  ConvGNImpl(int in, int out, int kernel, int stride);
  torch::Tensor forward(const torch::Tensor& x);
  CirConv conv{nullptr};
  torch::nn::GroupNorm norm{nullptr};
};
TORCH_MODULE(ConvGN);

// Input: image + GMNet outputs (3+3+1+3+1+1 = 12 channels) at the rendering resolution
// (H, W multiples of 16). Output: per-pixel probes in log space, log(1 + L) >= 0 (softplus),
// [B, H, W, h, w, 3].
// light_head: the last two layers i128-o128 k3 + ReLU + i128-o(h*w*3) k1 instead of A.2's
// i128-o512 k3 + ReLU + i512-o(h*w*3) k3 (36x fewer operations there; docs/model.md).
struct LNetImpl : torch::nn::Module {
  LNetImpl(int probe_height, int probe_width, int div = 1, bool light_head = false);
  torch::Tensor forward(const torch::Tensor& input);
  int h, w;
  ConvGN head{nullptr}, e1{nullptr}, e2{nullptr}, e3{nullptr}, e4{nullptr}, e5{nullptr};
  ConvGN d1{nullptr}, d2{nullptr}, d3{nullptr}, d4{nullptr}, d5{nullptr};
  CirConv out1{nullptr}, out2{nullptr};

 private:
  // The output layer and softplus on out1's activated features, without a gradient.
  torch::Tensor probes_without_gradient(const torch::Tensor& features);
};
TORCH_MODULE(LNet);

// LNet's 12-channel input from the image and GMNet's outputs (resized to H x W by area).
torch::Tensor lnet_input(const torch::Tensor& image, const GMOutput& gm, int height, int width);

// --- GSNet (sec. 3.2, Wu et al. 2018's fast trainable guided filter) -----------------------

// Box mean over a (2r+1)^2 window with CirP (wrap in W, replicate in H).
torch::Tensor box_mean(const torch::Tensor& x, int radius);

struct GSNetImpl : torch::nn::Module {
  explicit GSNetImpl(int radius = 2);
  // Refines base colour (3), roughness (1) and normal (3). The guided filter's linear
  // coefficients are fitted at half resolution and applied at full resolution, guided by a
  // learned 7-channel guide map computed from the image.
  GMOutput forward(const torch::Tensor& image, const GMOutput& coarse);
  int radius;
  torch::nn::Sequential guide{nullptr};
  torch::Tensor log_eps;  // the filter's regulariser, learned in log space
};
TORCH_MODULE(GSNet);

// Probe layout helpers.
torch::Tensor probes_to_mosaic(const torch::Tensor& probes);  // [B,H,W,h,w,3] -> [B,3,H*h,W*w]
torch::Tensor mosaic_to_probes(const torch::Tensor& mosaic, int h, int w);

}  // namespace phyir::model
