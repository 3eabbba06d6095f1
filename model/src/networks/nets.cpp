// GMNet (A.1), LNet (A.2), GSNet (sec. 3.2) in LibTorch.
#include "nets.h"

namespace F = torch::nn::functional;

namespace phyir::model {

namespace {

// The padded image's rows [top, top + H) are x's rows with `left` columns wrapped in from the
// right edge and `right` from the left; a pad wider than the image wraps more than once (tiny
// test inputs), so the source is x repeated until it is wide enough.
void copy_wrapped_rows(torch::Tensor dst_rows, const torch::Tensor& src_rows, int left, int right) {
  torch::Tensor wide = src_rows;
  while (wide.size(3) < std::max(left, right)) wide = torch::cat({wide, src_rows}, 3);
  const int64_t W = src_rows.size(3), Ww = wide.size(3);
  const auto fit = [&](const torch::Tensor& s) { return s.expand({s.size(0), s.size(1), dst_rows.size(2), s.size(3)}); };
  dst_rows.narrow(3, left, W).copy_(fit(src_rows));
  if (left > 0) dst_rows.narrow(3, 0, left).copy_(fit(wide.narrow(3, Ww - left, left)));
  if (right > 0) dst_rows.narrow(3, left + W, right).copy_(fit(wide.narrow(3, 0, right)));
}

// CirP written into one new tensor (x's memory format kept), instead of a concatenation and
// a replicate pad that copied the whole image twice (replication_pad2d alone was 12% of
// GMNet's time). The replicated top and bottom rows are copied from x's first and last row.
torch::Tensor cirpad4(const torch::Tensor& x, int top, int bottom, int left, int right) {
  const int64_t B = x.size(0), C = x.size(1), H = x.size(2), W = x.size(3);
  torch::Tensor y = torch::empty({B, C, H + top + bottom, W + left + right},
                                 x.options().memory_format(x.suggest_memory_format()));
  copy_wrapped_rows(y.narrow(2, top, H), x, left, right);
  if (top > 0) copy_wrapped_rows(y.narrow(2, 0, top), x.narrow(2, 0, 1), left, right);
  if (bottom > 0) copy_wrapped_rows(y.narrow(2, top + H, bottom), x.narrow(2, H - 1, 1), left, right);
  return y;
}

torch::Tensor up2(const torch::Tensor& x) {
  return F::interpolate(x, F::InterpolateFuncOptions()
                               .scale_factor(std::vector<double>{2.0, 2.0})
                               .mode(torch::kNearest));
}

torch::Tensor area_resize(const torch::Tensor& x, int h, int w) {
  if (x.size(2) == h && x.size(3) == w) return x;
  return F::adaptive_avg_pool2d(x, F::AdaptiveAvgPool2dFuncOptions({h, w}));
}

}  // namespace

bool convolve_with_onednn(const torch::Tensor& x) {
  return !torch::GradMode::is_enabled() && x.is_cpu() && x.scalar_type() == torch::kFloat && at::hasMKLDNN();
}

torch::Tensor normalize_channels(const torch::Tensor& x, double eps) {
  if (torch::GradMode::is_enabled()) return F::normalize(x, F::NormalizeFuncOptions().dim(1).eps(eps));
  return x / (x * x).sum(1, true).sqrt().clamp_min(eps);
}

torch::Tensor cirpad(const torch::Tensor& x, int pad_h, int pad_w) {
  return cirpad4(x, pad_h, pad_h, pad_w, pad_w);
}

CirConvImpl::CirConvImpl(int in, int out, int kernel, int stride, bool bias)
    : pad_lo((kernel - 1) / 2), pad_hi(kernel / 2) {
  conv = register_module(
      "conv", torch::nn::Conv2d(torch::nn::Conv2dOptions(in, out, kernel).stride(stride).bias(bias)));
}

torch::Tensor CirConvImpl::forward(const torch::Tensor& x) {
  const torch::Tensor padded = cirpad4(x, pad_lo, pad_hi, pad_lo, pad_hi);
  if (!convolve_with_onednn(padded)) return conv->forward(padded);
  // ATen sends a batch-1 convolution whose input holds at most 20480 values (LNet's 2x4
  // bottleneck at the default size) to im2col + BLAS, Debian's reference BLAS: oneDNN directly.
  return onednn_forward(padded, conv->weight, conv->bias);
}

torch::Tensor CirConvImpl::forward_reordered(const torch::Tensor& x, const torch::Tensor& order) {
  TORCH_CHECK(convolve_with_onednn(x), "CirConv::forward_reordered: without a gradient, float on the CPU only");
  const torch::Tensor bias = conv->bias.defined() ? conv->bias.index_select(0, order) : torch::Tensor();
  return onednn_forward(cirpad4(x, pad_lo, pad_hi, pad_lo, pad_hi), conv->weight.index_select(0, order), bias);
}

torch::Tensor CirConvImpl::onednn_forward(const torch::Tensor& padded, const torch::Tensor& weight,
                                          const torch::Tensor& bias) const {
  const c10::optional<torch::Tensor> b = bias.defined() ? c10::optional<torch::Tensor>(bias) : c10::nullopt;
  return at::mkldnn_convolution(padded, weight, b, {0, 0}, conv->options.stride(), {1, 1}, 1);
}

// --- GMNet ---------------------------------------------------------------------------------

BasicBlockImpl::BasicBlockImpl(int in, int out, int stride) {
  conv1 = register_module("conv1", CirConv(in, out, 3, stride, false));
  bn1 = register_module("bn1", SharedBatchNorm2d(out));
  conv2 = register_module("conv2", CirConv(out, out, 3, 1, false));
  bn2 = register_module("bn2", SharedBatchNorm2d(out));
  if (stride != 1 || in != out) {
    down = register_module(
        "down", torch::nn::Conv2d(torch::nn::Conv2dOptions(in, out, 1).stride(stride).bias(false)));
    down_bn = register_module("down_bn", SharedBatchNorm2d(out));
  }
}

torch::Tensor BasicBlockImpl::forward(const torch::Tensor& x) {
  torch::Tensor y = torch::relu(bn1->forward(conv1->forward(x)));
  y = bn2->forward(conv2->forward(y));
  const torch::Tensor identity = down ? down_bn->forward(down->forward(x)) : x;
  return torch::relu(y + identity);
}

ResNet18EncoderImpl::ResNet18EncoderImpl(int div) {
  auto c = [div](int n) { return n / div; };
  conv1 = register_module("conv1", CirConv(3, c(64), 7, 2, false));
  bn1 = register_module("bn1", SharedBatchNorm2d(c(64)));
  auto layer = [](int in, int out, int stride) {
    return torch::nn::Sequential(BasicBlock(in, out, stride), BasicBlock(out, out, 1));
  };
  layer1 = register_module("layer1", layer(c(64), c(64), 1));
  layer2 = register_module("layer2", layer(c(64), c(128), 2));
  layer3 = register_module("layer3", layer(c(128), c(256), 2));
  layer4 = register_module("layer4", layer(c(256), c(512), 2));
  // He initialisation for convolutions, as torchvision's ResNet.
  for (auto& m : modules(false)) {
    if (auto* c = m->as<torch::nn::Conv2d>())
      torch::nn::init::kaiming_normal_(c->weight, 0.0, torch::kFanOut, torch::kReLU);
  }
}

std::vector<torch::Tensor> ResNet18EncoderImpl::forward(const torch::Tensor& x) {
  const torch::Tensor s0 = torch::relu(bn1->forward(conv1->forward(x)));  // 1/2, 64
  torch::Tensor y = F::max_pool2d(cirpad(s0, 1, 1), F::MaxPool2dFuncOptions(3).stride(2));
  const torch::Tensor s1 = layer1->forward(y);   // 1/4, 64
  const torch::Tensor s2 = layer2->forward(s1);  // 1/8, 128
  const torch::Tensor s3 = layer3->forward(s2);  // 1/16, 256
  const torch::Tensor b = layer4->forward(s3);   // 1/32, 512
  return {s0, s1, s2, s3, b};
}

DecoderImpl::DecoderImpl(int out_channels, int div) {
  convs = register_module("convs", torch::nn::ModuleList());
  const int io[11][2] = {{512, 256}, {512, 256}, {256, 128}, {256, 128}, {128, 64}, {128, 64},
                         {64, 32},   {96, 32},   {32, 16},   {16, 16},   {16, 0}};
  for (const auto& c : io) convs->push_back(CirConv(c[0] / div, c[1] == 0 ? out_channels : c[1] / div, 3));
}

torch::Tensor DecoderImpl::forward(const std::vector<torch::Tensor>& f) {
  auto conv = [&](int i, const torch::Tensor& x) { return convs[i]->as<CirConv>()->forward(x); };
  auto act = [](const torch::Tensor& x) { return torch::elu(x); };
  torch::Tensor x = up2(act(conv(0, f[4])));
  x = torch::cat({x, f[3]}, 1);
  x = up2(act(conv(2, act(conv(1, x)))));
  x = torch::cat({x, f[2]}, 1);
  x = up2(act(conv(4, act(conv(3, x)))));
  x = torch::cat({x, f[1]}, 1);
  x = up2(act(conv(6, act(conv(5, x)))));
  x = torch::cat({x, f[0]}, 1);
  x = up2(act(conv(8, act(conv(7, x)))));
  return conv(10, act(conv(9, x)));  // the output layer has no activation
}

GMNetImpl::GMNetImpl(int div) {
  TORCH_CHECK(div >= 1 && 16 % div == 0, "GMNet: width divisor ", div, " must divide 16");
  encoder = register_module("encoder", ResNet18Encoder(div));
  depth = register_module("depth", Decoder(1, div));
  normal = register_module("normal", Decoder(3, div));
  base_color = register_module("base_color", Decoder(3, div));
  roughness = register_module("roughness", Decoder(1, div));
  metalness = register_module("metalness", Decoder(1, div));
}

GMOutput GMNetImpl::forward(const torch::Tensor& image) {
  TORCH_CHECK(image.dim() == 4 && image.size(1) == 3 && image.size(2) % 32 == 0 &&
                  image.size(3) % 32 == 0,
              "GMNet: input must be [B,3,H,W] with H and W multiples of 32, got ", image.sizes());
  const std::vector<torch::Tensor> f = encoder->forward(image * 2.0 - 1.0);
  GMOutput out;
  out.depth = F::softplus(depth->forward(f)) + 1e-3;  // metres, strictly positive
  out.normal = normalize_channels(normal->forward(f));
  out.base_color = torch::sigmoid(base_color->forward(f));
  out.roughness = torch::sigmoid(roughness->forward(f));
  out.metalness = torch::sigmoid(metalness->forward(f));
  return out;
}

void GMNetImpl::load_encoder(const std::string& path) {
  torch::load(encoder, path);
}

// --- LNet ----------------------------------------------------------------------------------

ConvGNImpl::ConvGNImpl(int in, int out, int kernel, int stride) {
  conv = register_module("conv", CirConv(in, out, kernel, stride));
  norm = register_module("norm", torch::nn::GroupNorm(out / 16, out));  // 16 channels per group
}

torch::Tensor ConvGNImpl::forward(const torch::Tensor& x) {
  return torch::relu(norm->forward(conv->forward(x)));
}

LNetImpl::LNetImpl(int probe_height, int probe_width, int div, bool light_head)
    : h(probe_height), w(probe_width) {
  TORCH_CHECK(div >= 1 && 4 % div == 0, "LNet: width divisor ", div, " must divide 4 (16-channel groups)");
  auto c = [div](int n) { return n / div; };
  // ("head", not "in": module names must not be Python keywords for torch::save.)
  head = register_module("head", ConvGN(12, c(64), 3, 1));
  e1 = register_module("e1", ConvGN(c(64), c(128), 4, 2));
  e2 = register_module("e2", ConvGN(c(128), c(256), 4, 2));
  e3 = register_module("e3", ConvGN(c(256), c(256), 4, 2));
  e4 = register_module("e4", ConvGN(c(256), c(512), 4, 2));
  e5 = register_module("e5", ConvGN(c(512), c(1024), 3, 1));
  d1 = register_module("d1", ConvGN(c(1024), c(512), 1, 1));
  d2 = register_module("d2", ConvGN(c(1024), c(256), 3, 1));
  d3 = register_module("d3", ConvGN(c(512), c(256), 3, 1));
  d4 = register_module("d4", ConvGN(c(512), c(128), 3, 1));
  d5 = register_module("d5", ConvGN(c(256), c(128), 3, 1));
  if (light_head) {
    // Our deviation (docs/model.md): A.2's 3x3 i512-o(h w 3) layer costs 232 GMAC at 128x256
    // with 16x32 probes; a 1x1 output layer on 128 channels costs 6.4 (same receptive field
    // up to one pixel, same output).
    out1 = register_module("out1", CirConv(c(128), c(128), 3));
    out2 = register_module("out2", CirConv(c(128), h * w * 3, 1));
  } else {
    out1 = register_module("out1", CirConv(c(128), c(512), 3));
    out2 = register_module("out2", CirConv(c(512), h * w * 3, 3));
  }
}

torch::Tensor LNetImpl::forward(const torch::Tensor& input) {
  TORCH_CHECK(input.dim() == 4 && input.size(1) == 12 && input.size(2) % 16 == 0 &&
                  input.size(3) % 16 == 0,
              "LNet: input must be [B,12,H,W] with H and W multiples of 16, got ", input.sizes());
  const torch::Tensor x0 = head->forward(input);
  const torch::Tensor x1 = e1->forward(x0);  // 1/2, 128
  const torch::Tensor x2 = e2->forward(x1);  // 1/4, 256
  const torch::Tensor x3 = e3->forward(x2);  // 1/8, 256
  const torch::Tensor x4 = e4->forward(x3);  // 1/16, 512
  const torch::Tensor x5 = e5->forward(x4);  // 1/16, 1024
  torch::Tensor y = torch::cat({d1->forward(x5), x4}, 1);   // 1024
  y = torch::cat({up2(d2->forward(y)), x3}, 1);             // 512 at 1/8
  y = torch::cat({up2(d3->forward(y)), x2}, 1);             // 512 at 1/4
  y = torch::cat({up2(d4->forward(y)), x1}, 1);             // 256 at 1/2
  y = up2(d5->forward(y));                                  // 128 at 1/1
  y = torch::relu(out1->forward(y));
  if (convolve_with_onednn(y)) return probes_without_gradient(y);
  // log(1 + L) >= 0 so that L = expm1(.) is a non-negative radiance everywhere.
  y = F::softplus(out2->forward(y));  // h*w*3
  const int64_t B = y.size(0), H = y.size(2), W = y.size(3);
  return y.view({B, 3, h, w, H, W}).permute({0, 4, 5, 2, 3, 1}).contiguous();
}

// The output layer's channels are (colour, probe row, probe column); taken in the order
// (row, column, colour) and written channels-last, its [B, h*w*3, H, W] output already is
// [B, H, W, h, w, 3] in memory. At the paper's size that saves three passes over 201 MB
// (oneDNN's reorder to NCHW, a new tensor for softplus, the permutation): the same numbers up
// to float rounding (tested against the path with a gradient).
torch::Tensor LNetImpl::probes_without_gradient(const torch::Tensor& features) {
  const torch::Tensor order = torch::arange(3 * h * w, torch::kLong).view({3, h * w}).t().reshape({-1});
  torch::Tensor y = out2->forward_reordered(features.contiguous(torch::MemoryFormat::ChannelsLast), order);
  y = y.permute({0, 2, 3, 1});  // [B, H, W, h*w*3], contiguous
  TORCH_CHECK(y.is_contiguous(), "LNet: oneDNN's output layer did not write channels-last");
  at::softplus_out(y, y, 1.0, 20.0);  // F::softplus's defaults, in place
  return y.view({y.size(0), y.size(1), y.size(2), h, w, 3});
}

torch::Tensor lnet_input(const torch::Tensor& image, const GMOutput& gm, int height, int width) {
  return torch::cat({area_resize(image, height, width),
                     normalize_channels(area_resize(gm.normal, height, width)),
                     area_resize(gm.depth, height, width), area_resize(gm.base_color, height, width),
                     area_resize(gm.roughness, height, width), area_resize(gm.metalness, height, width)},
                    1);
}

// --- GSNet ---------------------------------------------------------------------------------

torch::Tensor box_mean(const torch::Tensor& x, int radius) {
  const int k = 2 * radius + 1;
  return F::avg_pool2d(cirpad(x, radius, radius), F::AvgPool2dFuncOptions(k).stride(1));
}

GSNetImpl::GSNetImpl(int r) : radius(r) {
  guide = register_module(
      "guide", torch::nn::Sequential(CirConv(3, 16, 3), torch::nn::ELU(), CirConv(16, 16, 3),
                                     torch::nn::ELU(), torch::nn::Conv2d(torch::nn::Conv2dOptions(16, 7, 1))));
  log_eps = register_parameter("log_eps", torch::full({1}, std::log(1e-2)));
}

GMOutput GSNetImpl::forward(const torch::Tensor& image, const GMOutput& coarse) {
  const int64_t H = image.size(2), W = image.size(3);
  TORCH_CHECK(H % 2 == 0 && W % 2 == 0, "GSNet: H and W must be even, got ", image.sizes());
  const torch::Tensor p = torch::cat({coarse.base_color, coarse.roughness, coarse.normal}, 1);
  const auto half = F::AvgPool2dFuncOptions(2).stride(2);
  // Fit the guided filter's linear model q = A g + b at half resolution ...
  const torch::Tensor g_lo = guide->forward(F::avg_pool2d(image, half));
  const torch::Tensor p_lo = F::avg_pool2d(p, half);
  const torch::Tensor eps = torch::exp(log_eps);
  const torch::Tensor mean_g = box_mean(g_lo, radius);
  const torch::Tensor mean_p = box_mean(p_lo, radius);
  const torch::Tensor cov = box_mean(g_lo * p_lo, radius) - mean_g * mean_p;
  const torch::Tensor var = (box_mean(g_lo * g_lo, radius) - mean_g * mean_g).clamp_min(0.0);
  const torch::Tensor A = cov / (var + eps);
  const torch::Tensor b = mean_p - A * mean_g;
  // ... and apply it at full resolution with the full-resolution guide.
  const auto up = F::InterpolateFuncOptions()
                      .size(std::vector<int64_t>{H, W})
                      .mode(torch::kBilinear)
                      .align_corners(false);
  const torch::Tensor A_hi = F::interpolate(box_mean(A, radius), up);
  const torch::Tensor b_hi = F::interpolate(box_mean(b, radius), up);
  const torch::Tensor q = A_hi * guide->forward(image) + b_hi;
  GMOutput out = coarse;
  out.base_color = q.narrow(1, 0, 3).clamp(0.0, 1.0);
  out.roughness = q.narrow(1, 3, 1).clamp(0.0, 1.0);
  out.normal = normalize_channels(q.narrow(1, 4, 3));
  return out;
}

// --- Probe layout --------------------------------------------------------------------------

torch::Tensor probes_to_mosaic(const torch::Tensor& probes) {
  const int64_t B = probes.size(0), H = probes.size(1), W = probes.size(2), h = probes.size(3),
                w = probes.size(4);
  return probes.permute({0, 5, 1, 3, 2, 4}).reshape({B, 3, H * h, W * w});
}

torch::Tensor mosaic_to_probes(const torch::Tensor& mosaic, int h, int w) {
  const int64_t B = mosaic.size(0), H = mosaic.size(2) / h, W = mosaic.size(3) / w;
  TORCH_CHECK(mosaic.size(2) == H * h && mosaic.size(3) == W * w, "probe mosaic ", mosaic.sizes(),
              " is not a grid of ", h, " x ", w, " probes");
  return mosaic.view({B, 3, H, h, W, w}).permute({0, 2, 4, 3, 5, 1}).contiguous();
}

}  // namespace phyir::model
