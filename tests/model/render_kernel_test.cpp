// The fused rendering-layer kernel (render_kernel.cpp) against the torch-composed reference
// (render_layer_reference) on the same uniforms: values and every gradient (normal, base colour,
// roughness, metalness, probes), including mirror pixels, grazing and back-facing normals; and
// independence of the thread count.
#include "render_kernel.h"
#include "render_layer.h"

namespace pm = phyir::model;

namespace {

struct Case {
  torch::Tensor n, base, rough, metal, probes;
};

// Random maps on an H x W panorama: normals near the view direction (some grazing, some
// facing away), roughness across the mirror threshold, metalness in [0,1].
Case random_case(int H, int W, int h, int w, torch::Dtype dt) {
  const auto o = torch::TensorOptions().dtype(dt);
  Case c;
  const torch::Tensor v = -pm::pixel_directions(H, W, o).permute({2, 0, 1}).unsqueeze(0);
  c.n = (v + 0.9 * (torch::rand({1, 3, H, W}, o) - 0.5)) * (0.5 + torch::rand({1, 1, H, W}, o));  // unnormalised
  c.base = torch::rand({1, 3, H, W}, o);
  c.rough = torch::rand({1, 1, H, W}, o);
  c.rough.view(-1).narrow(0, 0, 4).copy_(torch::tensor({0.0, 0.004, 0.0079, 0.009}, o));  // mirror and near it
  c.metal = torch::rand({1, 1, H, W}, o);
  c.probes = torch::rand({1, H, W, h, w, 3}, o) * 3.0;
  return c;
}

std::vector<torch::Tensor> leaves(Case& c) {
  for (torch::Tensor* t : {&c.n, &c.base, &c.rough, &c.metal, &c.probes}) t->set_requires_grad(true);
  return {c.n, c.base, c.rough, c.metal, c.probes};
}

}  // namespace

TEST(ModelRenderKernel, MatchesTheReferenceInValuesAndGradients) {
  torch::set_num_threads(1);
  const int H = 8, W = 16, h = 4, w = 8, nd = 8, ns = 8;
  const uint64_t seed = 12345;
  torch::manual_seed(3);
  Case a = random_case(H, W, h, w, torch::kDouble);
  Case b{a.n.clone(), a.base.clone(), a.rough.clone(), a.metal.clone(), a.probes.clone()};
  const auto la = leaves(a), lb = leaves(b);
  const torch::Tensor weights = torch::rand({1, 3, H, W}, torch::kDouble);
  const torch::Tensor wd = torch::rand({1, 3, H, W}, torch::kDouble);

  // Kernel: the layer's flattening, called with a fixed seed.
  const torch::Tensor v = -pm::pixel_directions(H, W, torch::TensorOptions().dtype(torch::kDouble)).reshape({H * W, 3});
  auto flat = [&](const torch::Tensor& x) { return x.permute({0, 2, 3, 1}).reshape({H * W, x.size(1)}); };
  const auto k = pm::render_pixels_fused(flat(a.n), v, flat(a.base), flat(a.rough), flat(a.metal),
                                         a.probes.reshape({H * W, h, w, 3}), nd, ns, seed);
  auto [ud, us] = pm::render_uniforms(H * W, nd, ns, seed, torch::kDouble);
  const auto r = pm::render_layer_reference(b.n, b.base, b.rough, b.metal, b.probes, ud, us);
  const torch::Tensor kd = k.diffuse.view({1, H, W, 3}).permute({0, 3, 1, 2});
  const torch::Tensor ks = k.specular.view({1, H, W, 3}).permute({0, 3, 1, 2});
  // Not bit-equal: the reference rounds some constants to float (its diffuse lobe multiplies
  // by float(1/pi) * float(pi) = 1 + 2.8e-8).
  EXPECT_TRUE(torch::allclose(kd, r.diffuse, 1e-7, 1e-12)) << (kd - r.diffuse).abs().max().item<double>();
  EXPECT_TRUE(torch::allclose(ks, r.specular, 1e-7, 1e-12)) << (ks - r.specular).abs().max().item<double>();
  EXPECT_GT(r.specular.abs().sum().item<double>(), 1.0);  // not vacuous
  ((kd * wd).sum() + (ks * weights).sum()).backward();
  ((r.diffuse * wd).sum() + (r.specular * weights).sum()).backward();
  const char* names[] = {"normal", "base colour", "roughness", "metalness", "probes"};
  for (size_t i = 0; i < la.size(); ++i) {
    const torch::Tensor ga = la[i].grad(), gb = lb[i].grad();
    ASSERT_TRUE(ga.defined() && gb.defined()) << names[i];
    EXPECT_LE((ga - gb).abs().max().item<double>(), 1e-7 * gb.abs().max().item<double>())
        << names[i] << ": max difference " << (ga - gb).abs().max().item<double>() << " of "
        << gb.abs().max().item<double>();
    EXPECT_GT(gb.abs().max().item<double>(), 0.0) << names[i];
  }
}

TEST(ModelRenderKernel, FloatMatchesDoubleAndThreadCountDoesNotMatter) {
  const int H = 8, W = 16;
  torch::manual_seed(5);
  Case c = random_case(H, W, 4, 8, torch::kFloat);
  pm::RenderSettings s{32, 16, 4096};
  auto run = [&](int threads, torch::Dtype dt) {
    torch::set_num_threads(threads);
    torch::manual_seed(77);
    auto o = pm::render_layer(c.n.to(dt), c.base.to(dt), c.rough.to(dt), c.metal.to(dt), c.probes.to(dt), s);
    torch::set_num_threads(1);
    return o.image.to(torch::kDouble);
  };
  const torch::Tensor one = run(1, torch::kFloat), two = run(2, torch::kFloat), dbl = run(1, torch::kDouble);
  EXPECT_TRUE(torch::equal(one, two));
  EXPECT_TRUE(torch::allclose(one, dbl, 1e-4, 1e-5)) << (one - dbl).abs().max().item<double>();
}

// The kernel's pixels are split between the threads (200 pixels: several per thread, and not a
// multiple of its 64 bands, so the last band is short); each pixel draws from its own stream and
// writes only its own gradients, so values and every gradient are equal with 1 and 2 threads.
TEST(ModelRenderKernel, GradientsDoNotDependOnThreadCount) {
  const int H = 10, W = 20;
  torch::manual_seed(9);
  const Case base = random_case(H, W, 4, 8, torch::kFloat);
  const torch::Tensor wd = torch::rand({1, 3, H, W}), ws = torch::rand({1, 3, H, W});
  auto run = [&](int threads) {
    Case c{base.n.clone(), base.base.clone(), base.rough.clone(), base.metal.clone(), base.probes.clone()};
    const auto inputs = leaves(c);
    torch::set_num_threads(threads);
    torch::manual_seed(77);
    const auto o = pm::render_layer(c.n, c.base, c.rough, c.metal, c.probes, pm::RenderSettings{32, 16, 4096});
    ((o.diffuse * wd).sum() + (o.specular * ws).sum()).backward();
    torch::set_num_threads(1);
    std::vector<torch::Tensor> out{o.diffuse.detach(), o.specular.detach()};
    for (const torch::Tensor& x : inputs) out.push_back(x.grad());
    return out;
  };
  const auto one = run(1), two = run(2);
  const char* names[] = {"diffuse", "specular", "normal", "base colour", "roughness", "metalness", "probes"};
  for (size_t i = 0; i < one.size(); ++i) {
    ASSERT_TRUE(one[i].defined()) << names[i];
    EXPECT_TRUE(torch::equal(one[i], two[i])) << names[i];
  }
  EXPECT_GT(one[6].abs().sum().item<double>(), 0.0);  // not vacuous
}
