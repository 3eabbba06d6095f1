// GMNet, LNet, GSNet: shapes, output ranges, circular padding, probe layout.
#include "nets.h"

namespace pm = phyir::model;

namespace {
struct ThreadSetup {
  ThreadSetup() { torch::set_num_threads(1); }  // shared machines: no OpenMP spinning
} thread_setup;
}  // namespace

TEST(ModelNets, CirPadWrapsWidthAndReplicatesHeight) {
  const auto x = torch::arange(6, torch::kFloat).view({1, 1, 2, 3});  // [[0,1,2],[3,4,5]]
  const auto y = pm::cirpad(x, 1, 1);
  ASSERT_EQ(y.sizes(), torch::IntArrayRef({1, 1, 4, 5}));
  const float expect[4][5] = {{2, 0, 1, 2, 0}, {2, 0, 1, 2, 0}, {5, 3, 4, 5, 3}, {5, 3, 4, 5, 3}};
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 5; ++c) EXPECT_EQ(y[0][0][r][c].item<float>(), expect[r][c]) << r << "," << c;
}

TEST(ModelNets, GMNetShapesRangesAndCircularEquivariance) {
  torch::manual_seed(1);
  pm::GMNet net;
  net->eval();
  torch::NoGradGuard ng;
  const auto x = torch::rand({1, 3, 32, 128});
  const pm::GMOutput o = net->forward(x);
  EXPECT_EQ(o.depth.sizes(), torch::IntArrayRef({1, 1, 32, 128}));
  EXPECT_EQ(o.normal.sizes(), torch::IntArrayRef({1, 3, 32, 128}));
  EXPECT_EQ(o.base_color.sizes(), torch::IntArrayRef({1, 3, 32, 128}));
  EXPECT_GT(o.depth.min().item<float>(), 0.0f);
  EXPECT_NEAR((o.normal.norm(2, 1) - 1.0).abs().max().item<float>(), 0.0f, 1e-5);
  for (const auto* t : {&o.base_color, &o.roughness, &o.metalness}) {
    EXPECT_GE(t->min().item<float>(), 0.0f);
    EXPECT_LE(t->max().item<float>(), 1.0f);
  }
  // CirP everywhere: rotating the panorama by a multiple of the encoder's stride (32 columns)
  // rotates every output by the same amount, seam included.
  const pm::GMOutput r = net->forward(x.roll(32, 3));
  EXPECT_LT((r.depth - o.depth.roll(32, 3)).abs().max().item<float>(), 1e-4);
  EXPECT_LT((r.normal - o.normal.roll(32, 3)).abs().max().item<float>(), 1e-4);
  EXPECT_LT((r.base_color - o.base_color.roll(32, 3)).abs().max().item<float>(), 1e-4);
  // Parameter count: ResNet-18's convolutional trunk (11.2M without the classifier) + 5 decoders.
  int64_t n_enc = 0;
  for (const auto& p : net->encoder->parameters()) n_enc += p.numel();
  EXPECT_EQ(n_enc, 11176512);
}

TEST(ModelNets, GMNetTrainsOneStep) {
  torch::manual_seed(2);
  pm::GMNet net(4);  // a quarter of the channels: quick
  net->train();
  const auto x = torch::rand({2, 3, 32, 64});
  const pm::GMOutput o = net->forward(x);
  const auto loss = o.depth.mean() + o.normal.mean() + o.base_color.mean() + o.roughness.mean() + o.metalness.mean();
  loss.backward();
  for (const auto& p : net->parameters()) ASSERT_TRUE(torch::isfinite(p.grad()).all().item<bool>());
}

TEST(ModelNets, LNetProbeShapeAndLayout) {
  torch::manual_seed(3);
  pm::LNet net(4, 8, 4);
  const auto in = torch::rand({2, 12, 16, 32});
  const auto probes = net->forward(in);
  EXPECT_EQ(probes.sizes(), torch::IntArrayRef({2, 16, 32, 4, 8, 3}));
  EXPECT_GE(probes.min().item<float>(), 0.0f);  // log(1 + L) >= 0
  probes.sum().backward();
  for (const auto& p : net->parameters()) ASSERT_TRUE(torch::isfinite(p.grad()).all().item<bool>());
  // GroupNorm with 16-channel groups.
  EXPECT_EQ(net->e5->norm->options.num_groups(), 1024 / 4 / 16);
  EXPECT_EQ(pm::LNet(4, 8)->e5->norm->options.num_groups(), 1024 / 16);
  // Mosaic layout: probe (i, j) is the h x w block at row i*h, col j*w; round trip is exact.
  const auto mosaic = pm::probes_to_mosaic(probes.detach());
  EXPECT_EQ(mosaic.sizes(), torch::IntArrayRef({2, 3, 16 * 4, 32 * 8}));
  EXPECT_EQ(mosaic[1][2][5 * 4 + 3][7 * 8 + 6].item<float>(), probes[1][5][7][3][6][2].item<float>());
  EXPECT_TRUE(torch::equal(pm::mosaic_to_probes(mosaic, 4, 8), probes.detach()));
  // lnet_input: 3 + 3 + 1 + 3 + 1 + 1 = 12 channels at the requested size.
  pm::GMOutput gm{torch::ones({1, 1, 32, 64}), torch::ones({1, 3, 32, 64}), torch::ones({1, 3, 32, 64}),
                  torch::ones({1, 1, 32, 64}), torch::ones({1, 1, 32, 64})};
  EXPECT_EQ(pm::lnet_input(torch::ones({1, 3, 32, 64}), gm, 16, 32).sizes(), torch::IntArrayRef({1, 12, 16, 32}));
}

TEST(ModelNets, GSNetRefinesAtFullResolution) {
  torch::manual_seed(4);
  pm::GSNet net(2);
  const auto image = torch::rand({1, 3, 32, 64});
  pm::GMOutput coarse{torch::ones({1, 1, 32, 64}),
                      torch::nn::functional::normalize(torch::rand({1, 3, 32, 64}) - 0.5,
                                                       torch::nn::functional::NormalizeFuncOptions().dim(1)),
                      torch::rand({1, 3, 32, 64}), torch::rand({1, 1, 32, 64}), torch::rand({1, 1, 32, 64})};
  const pm::GMOutput out = net->forward(image, coarse);
  EXPECT_EQ(out.base_color.sizes(), torch::IntArrayRef({1, 3, 32, 64}));
  EXPECT_EQ(out.roughness.sizes(), torch::IntArrayRef({1, 1, 32, 64}));
  EXPECT_NEAR((out.normal.norm(2, 1) - 1.0).abs().max().item<float>(), 0.0f, 1e-5);
  EXPECT_TRUE(torch::equal(out.metalness, coarse.metalness));  // not refined
  (out.base_color.mean() + out.roughness.mean() + out.normal.mean()).backward();
  for (const auto& p : net->parameters()) ASSERT_TRUE(torch::isfinite(p.grad()).all().item<bool>());
  // A constant map is a fixed point of the guided filter (cov = 0 -> A = 0, b = the constant).
  pm::GMOutput flat = coarse;
  flat.base_color = torch::full({1, 3, 32, 64}, 0.25);
  flat.roughness = torch::full({1, 1, 32, 64}, 0.5);
  const pm::GMOutput f = net->forward(image, flat);
  EXPECT_LT((f.base_color - 0.25).abs().max().item<float>(), 1e-5);
  EXPECT_LT((f.roughness - 0.5).abs().max().item<float>(), 1e-5);
  // Box mean with CirP: the mean of a constant is the constant.
  EXPECT_LT((pm::box_mean(torch::full({1, 1, 8, 16}, 3.0), 2) - 3.0).abs().max().item<float>(), 1e-6);
}

// CirP before it was written into one tensor: a concatenation along the width, then a
// replicate pad along the height.
torch::Tensor cirpad_by_cat(const torch::Tensor& x, int pad_h, int pad_w) {
  torch::Tensor wide = x;
  while (wide.size(3) < pad_w) wide = torch::cat({wide, x}, 3);
  const torch::Tensor y = torch::cat({wide.narrow(3, wide.size(3) - pad_w, pad_w), x, wide.narrow(3, 0, pad_w)}, 3);
  return torch::nn::functional::pad(y, torch::nn::functional::PadFuncOptions({0, 0, pad_h, pad_h}).mode(torch::kReplicate));
}

TEST(ModelNets, CirPadEqualsConcatenationAndReplicatePadInValuesAndGradients) {
  torch::manual_seed(5);
  for (const auto& [pad_h, pad_w, width] : std::vector<std::tuple<int, int, int>>{{1, 1, 8}, {3, 3, 16}, {2, 5, 3}}) {
    const auto x = torch::rand({2, 3, 5, width}, torch::kDouble).requires_grad_(true);
    const auto w = torch::rand({2, 3, 5 + 2 * pad_h, width + 2 * pad_w}, torch::kDouble);
    const auto y = pm::cirpad(x, pad_h, pad_w);
    const auto r = cirpad_by_cat(x, pad_h, pad_w);
    EXPECT_TRUE(torch::equal(y, r)) << pad_h << " " << pad_w << " " << width;
    const auto gy = torch::autograd::grad({(y * w).sum()}, {x})[0];
    const auto gr = torch::autograd::grad({(r * w).sum()}, {x})[0];
    EXPECT_LT((gy - gr).abs().max().item<double>(), 1e-12);
    // Channels-last input: same values, layout kept.
    const auto xl = x.detach().contiguous(torch::MemoryFormat::ChannelsLast);
    const auto yl = pm::cirpad(xl, pad_h, pad_w);
    EXPECT_TRUE(yl.is_contiguous(torch::MemoryFormat::ChannelsLast));
    EXPECT_TRUE(torch::equal(yl, r.detach()));
  }
}

// Inference (no gradient: CirConv calls oneDNN itself) against the path training takes
// (gradient on: ATen chooses, im2col for the smallest inputs), on random weights.
TEST(ModelNets, InferencePathEqualsTrainingPathOnRandomWeights) {
  torch::manual_seed(6);
  const auto max_rel = [](const torch::Tensor& a, const torch::Tensor& b) {
    return ((a - b).abs().max() / b.abs().max().clamp_min(1e-12)).item<float>();
  };
  pm::GMNet gm(4);
  gm->eval();
  const auto image = torch::rand({1, 3, 64, 128});
  const pm::GMOutput slow = gm->forward(image);
  pm::GMOutput fast;
  {
    torch::NoGradGuard ng;
    fast = gm->forward(image);
  }
  EXPECT_LT(max_rel(fast.depth, slow.depth.detach()), 1e-4);
  EXPECT_LT(max_rel(fast.normal, slow.normal.detach()), 1e-4);
  EXPECT_LT(max_rel(fast.base_color, slow.base_color.detach()), 1e-4);
  EXPECT_LT(max_rel(fast.roughness, slow.roughness.detach()), 1e-4);
  EXPECT_LT(max_rel(fast.metalness, slow.metalness.detach()), 1e-4);
  // LNet with both heads, at a size whose 1/16 bottleneck ATen would send to im2col.
  for (const bool light : {false, true}) {
    pm::LNet ln(4, 8, 4, light);
    ln->eval();
    const auto in = torch::rand({1, 12, 32, 64});
    const auto slow_probes = ln->forward(in).detach();
    torch::NoGradGuard ng;
    const auto fast_probes = ln->forward(in);
    EXPECT_LT(max_rel(fast_probes, slow_probes), 1e-4) << (light ? "light" : "paper");
  }
}
