// Augmentation (model/src/data/augment.h): a rotated or mirrored sample, rendered by the rendering
// layer from its own ground-truth maps and probes, gives the rotated or mirrored image (and a
// transform with one part left out does not); a full turn and a double mirror are the
// identity; exposure jitter scales input and targets together; draws depend on the seed,
// the epoch and the view only, not on the thread count.
#include "augment.h"
#include "data.h"
#include "exposure.h"
#include "phyir/model/training.h"
#include "render_layer.h"

namespace pm = phyir::model;
namespace F = torch::nn::functional;

namespace {

// 64 x 32 input, 32 x 16 rendering grid, 8 x 16 probes: 16 exact rotations.
constexpr int kHi = 32, kWi = 64, kHr = 16, kWr = 32, kPh = 8, kPw = 16;

pm::ModelConfig config() {
  pm::ModelConfig c;
  c.input_height = kHi, c.input_width = kWi, c.render_height = kHr, c.render_width = kWr;
  c.probe_height = kPh, c.probe_width = kPw;
  return c;
}

// A view whose every part depends on direction and position, asymmetric in x and z, so a
// transform that forgets a part shows in the render.
pm::ViewTensors synthetic_view(uint64_t seed) {
  torch::manual_seed(seed);
  pm::ViewTensors v;
  const torch::Tensor d = pm::pixel_directions(kHi, kWi, torch::TensorOptions()).permute({2, 0, 1});  // [3,H,W]
  const torch::Tensor u = (torch::arange(kWi, torch::kFloat) + 0.5) / kWi, t = (torch::arange(kHi, torch::kFloat) + 0.5) / kHi;
  const torch::Tensor U = u.view({1, kWi}).expand({kHi, kWi}), T = t.view({kHi, 1}).expand({kHi, kWi});
  const torch::Tensor e = torch::stack({torch::sin(2 * M_PI * 3 * U), 0.5 * torch::cos(2 * M_PI * 2 * T),
                                        torch::cos(2 * M_PI * U + 1.0)});
  v.normal = F::normalize(-d + 0.6 * e, F::NormalizeFuncOptions().dim(0));
  v.image = torch::rand({3, kHi, kWi});
  v.depth = (2.0 + d[0] - 0.5 * d[2]).unsqueeze(0);
  v.base_color = 0.2 + 0.6 * torch::rand({3, kHi, kWi});
  v.roughness = 0.15 + 0.7 * torch::rand({1, kHi, kWi});
  v.metalness = (torch::rand({1, kHi, kWi}) > 0.7).to(torch::kFloat);
  v.mask = torch::ones({1, kHi, kWi});
  v.render_mask = torch::ones({1, kHr, kWr});
  v.probe_mask = torch::ones({1, kHr, kWr});
  // Probes: a sharp lobe and a broad one from fixed world directions, varying along the grid.
  const torch::Tensor td = pm::pixel_directions(kPh, kPw, torch::TensorOptions());  // [h,w,3]
  const torch::Tensor a = F::normalize(torch::tensor({0.8f, 0.3f, -0.5f}), F::NormalizeFuncOptions().dim(0));
  const torch::Tensor b = F::normalize(torch::tensor({-0.3f, 0.2f, 0.9f}), F::NormalizeFuncOptions().dim(0));
  const torch::Tensor lobe = 0.2 + 3.0 * (td.matmul(a)).clamp_min(0).pow(3) + 0.8 * td.matmul(b).clamp_min(0);  // [h,w]
  const torch::Tensor col = 1.0 + 0.5 * torch::sin(2 * M_PI * (torch::arange(kWr, torch::kFloat) + 0.5) / kWr + 0.3);
  const torch::Tensor row = 1.0 + 0.3 * torch::arange(kHr, torch::kFloat) / kHr;
  const torch::Tensor tint = torch::tensor({1.0f, 0.8f, 0.6f});
  v.probes = (row.view({kHr, 1, 1, 1, 1}) * col.view({1, kWr, 1, 1, 1}) * lobe.view({1, 1, kPh, kPw, 1}) *
              tint.view({1, 1, 1, 1, 3}))
                 .contiguous();
  return v;
}

// The rendering layer on a view's own maps (area-resized to the grid, as training does).
torch::Tensor render(const pm::ViewTensors& v, uint64_t seed) {
  torch::manual_seed(seed);
  auto lo = [](const torch::Tensor& x) { return pm::resize(x.unsqueeze(0), kHr, kWr); };
  pm::RenderSettings rs;
  rs.diffuse_samples = 512;
  rs.specular_samples = 256;
  const torch::Tensor n = F::normalize(lo(v.normal), F::NormalizeFuncOptions().dim(1).eps(1e-6));
  return pm::render_layer(n, lo(v.base_color), lo(v.roughness), lo(v.metalness), v.probes.unsqueeze(0), rs).image[0];
}

double relative_mse(const torch::Tensor& a, const torch::Tensor& b) {
  return ((a - b).square().sum() / b.square().sum()).item<double>();
}

bool same(const pm::ViewTensors& a, const pm::ViewTensors& b, double tol = 0.0) {
  for (torch::Tensor pm::ViewTensors::*m :
       {&pm::ViewTensors::image, &pm::ViewTensors::depth, &pm::ViewTensors::normal, &pm::ViewTensors::base_color,
        &pm::ViewTensors::roughness, &pm::ViewTensors::metalness, &pm::ViewTensors::mask, &pm::ViewTensors::color_lo,
        &pm::ViewTensors::render_mask, &pm::ViewTensors::probes, &pm::ViewTensors::probe_mask}) {
    const torch::Tensor &x = a.*m, &y = b.*m;
    if (x.defined() != y.defined()) return false;
    if (!x.defined()) continue;
    if (tol == 0.0 ? !torch::equal(x, y) : !torch::allclose(x, y, 0.0, tol)) return false;
  }
  return true;
}

class Augment : public ::testing::Test {
 protected:
  void SetUp() override {
    torch::set_num_threads(1);
    view_ = synthetic_view(3);
    view_.color_lo = render(view_, 100);  // the view's "ground truth" image
    noise_ = relative_mse(render(view_, 200), view_.color_lo);  // two independent renders
  }
  // Relative MSE of the augmented view's render against its (augmented) colour target.
  double error(const pm::ViewTensors& v) const { return relative_mse(render(v, 300), v.color_lo); }

  pm::ViewTensors view_;
  double noise_ = 0.0;
};

TEST_F(Augment, YawDivisionsAreExactForEveryGrid) {
  EXPECT_EQ(pm::yaw_divisions(config()), 16);
  pm::ModelConfig paper;
  paper.input_width = 512, paper.render_width = 256, paper.probe_width = 32;
  EXPECT_EQ(pm::yaw_divisions(paper), 32);
  EXPECT_EQ(pm::yaw_divisions(pm::ModelConfig{}), 16);  // defaults: 256, 64, 16
}

TEST_F(Augment, RotatedSampleRendersToTheRotatedImage) {
  const int n = pm::yaw_divisions(config());
  std::printf("[Augment] noise of two renders: relative MSE %.3g\n", noise_);
  ASSERT_LT(noise_, 0.01);
  for (int steps : {1, 5, 11}) {
    const pm::ViewTensors r = pm::rotate_view(view_, steps, n);
    const double e = error(r);
    std::printf("[Augment] rotation by %d/%d: relative MSE %.3g\n", steps, n, e);
    EXPECT_LT(e, 2.0 * noise_ + 1e-4) << steps;
    // Each part left out shows: normals not rotated, probes' texels not turned, probes not moved.
    pm::ViewTensors no_normal = r, no_texels = r, no_move = r;
    no_normal.normal = torch::roll(view_.normal, steps * kWi / n, -1);
    no_texels.probes = torch::roll(view_.probes, steps * kWr / n, 1);
    no_move.probes = torch::roll(view_.probes, steps * kPw / n, 3);
    EXPECT_GT(error(no_normal), 10.0 * noise_) << steps;
    EXPECT_GT(error(no_texels), 10.0 * noise_) << steps;
    EXPECT_GT(error(no_move), 10.0 * noise_) << steps;
  }
}

TEST_F(Augment, MirroredSampleRendersToTheMirroredImage) {
  const pm::ViewTensors m = pm::mirror_view(view_);
  const double e = error(m);
  std::printf("[Augment] mirror: relative MSE %.3g (noise %.3g)\n", e, noise_);
  EXPECT_LT(e, 2.0 * noise_ + 1e-4);
  pm::ViewTensors no_normal = m, no_texels = m;
  no_normal.normal = view_.normal.flip({-1});
  no_texels.probes = view_.probes.flip({1});
  EXPECT_GT(error(no_normal), 10.0 * noise_);
  EXPECT_GT(error(no_texels), 10.0 * noise_);
  // Rotation then mirror, as augment_view applies them.
  pm::AugmentDraw d;
  d.yaw_steps = 3;
  d.mirror = true;
  EXPECT_LT(error(pm::augment_view(view_, d, pm::yaw_divisions(config()))), 2.0 * noise_ + 1e-4);
}

TEST_F(Augment, FullTurnAndDoubleMirrorAreTheIdentity) {
  const int n = pm::yaw_divisions(config());
  EXPECT_TRUE(same(pm::rotate_view(view_, n, n), view_));  // a whole turn: exactly nothing to do
  pm::ViewTensors r = view_;
  for (int k = 0; k < n; ++k) r = pm::rotate_view(r, 1, n);  // n steps of 1/n: float rounding only
  EXPECT_TRUE(same(r, view_, 1e-5));
  EXPECT_FALSE(same(pm::rotate_view(view_, 1, n), view_, 1e-3));
  EXPECT_TRUE(same(pm::rotate_view(pm::rotate_view(view_, 5, n), n - 5, n), view_, 1e-6));
  EXPECT_TRUE(same(pm::mirror_view(pm::mirror_view(view_)), view_));
  // A quarter turn takes the azimuth from -Z (the centre column) to +X.
  const torch::Tensor z = torch::tensor({0.0f, 0.0f, -1.0f}).view({3, 1, 1});
  EXPECT_TRUE(torch::allclose(pm::rotate_about_y(z, 0.25), torch::tensor({1.0f, 0.0f, 0.0f}).view({3, 1, 1}), 0, 1e-6));
}

TEST_F(Augment, ExposureJitterScalesInputAndTargetsTogether) {
  const double stops = -1.3, f = std::exp2(stops);
  const pm::ViewTensors e = pm::expose_view(view_, stops);
  EXPECT_TRUE(torch::allclose(e.color_lo, view_.color_lo * f, 1e-6, 0));
  EXPECT_TRUE(torch::allclose(e.probes, view_.probes * f, 1e-6, 0));
  // The input re-exposed in linear and re-encoded: decode(image') = clip(f decode(image)).
  EXPECT_TRUE(torch::allclose(pm::srgb_decode(e.image), (pm::srgb_decode(view_.image) * f).clamp(0.0, 1.0), 0, 1e-5));
  // Brighter: pixels pushed past 1 clip.
  const pm::ViewTensors b = pm::expose_view(view_, 1.0);
  EXPECT_TRUE(torch::allclose(pm::srgb_decode(b.image), (pm::srgb_decode(view_.image) * 2.0).clamp(0.0, 1.0), 0, 1e-5));
  EXPECT_NEAR(b.image.max().item<float>(), 1.0f, 1e-6f);
  // The rendering layer is linear in the probes: the jittered view still renders to its target.
  EXPECT_LT(error(e), 2.0 * noise_ + 1e-4);
  EXPECT_TRUE(same(pm::expose_view(view_, 0.0), view_));
  // Absolute targets (--target-units absolute) keep the scene's radiance: only the input moves.
  const pm::ViewTensors a = pm::expose_view(view_, stops, phyir::view::RadianceUnits::kAbsolute);
  EXPECT_TRUE(torch::equal(a.image, e.image));
  EXPECT_TRUE(torch::equal(a.color_lo, view_.color_lo));
  EXPECT_TRUE(torch::equal(a.probes, view_.probes));
}

TEST_F(Augment, DrawsDependOnSeedEpochAndViewOnly) {
  pm::AugmentOptions o;
  const int n = 16;
  std::vector<int> steps_seen(n, 0);
  int mirrors = 0;
  for (size_t v = 0; v < 2000; ++v) {
    const pm::AugmentDraw d = pm::draw_augment(o, n, 7, 3, v);
    ASSERT_GE(d.yaw_steps, 0);
    ASSERT_LT(d.yaw_steps, n);
    ++steps_seen[d.yaw_steps];
    mirrors += d.mirror;
    EXPECT_GE(d.exposure_stops, o.exposure_min_stops);
    EXPECT_LT(d.exposure_stops, o.exposure_max_stops);
  }
  for (int k = 0; k < n; ++k) EXPECT_GT(steps_seen[k], 2000 / n / 2) << k;
  EXPECT_NEAR(mirrors / 2000.0, 0.5, 0.05);
  const pm::AugmentDraw a = pm::draw_augment(o, n, 7, 3, 11), b = pm::draw_augment(o, n, 7, 3, 11);
  EXPECT_EQ(a.yaw_steps, b.yaw_steps);
  EXPECT_EQ(a.exposure_stops, b.exposure_stops);
  EXPECT_NE(pm::draw_augment(o, n, 7, 4, 11).exposure_stops, a.exposure_stops);  // another epoch
  EXPECT_NE(pm::draw_augment(o, n, 8, 3, 11).exposure_stops, a.exposure_stops);  // another seed
  // Options off: identity draws; one option off leaves the others' draws unchanged.
  pm::AugmentOptions off;
  off.enabled = false;
  const pm::AugmentDraw z = pm::draw_augment(off, n, 7, 3, 11);
  EXPECT_EQ(z.yaw_steps, 0);
  EXPECT_FALSE(z.mirror);
  EXPECT_EQ(z.exposure_stops, 0.0);
  pm::AugmentOptions no_rotate;
  no_rotate.rotate = false;
  EXPECT_EQ(pm::draw_augment(no_rotate, n, 7, 3, 11).yaw_steps, 0);
  EXPECT_EQ(pm::draw_augment(no_rotate, n, 7, 3, 11).exposure_stops, a.exposure_stops);
}

TEST_F(Augment, SameSeedSameBatchWhateverTheThreadCount) {
  std::vector<pm::ViewTensors> views;
  for (uint64_t s = 0; s < 4; ++s) {
    pm::ViewTensors v = synthetic_view(10 + s);
    v.color_lo = torch::rand({3, kHr, kWr});
    views.push_back(v);
  }
  pm::AugmentOptions o;
  const int n = pm::yaw_divisions(config());
  const std::vector<size_t> idx = {2, 0, 3};
  torch::set_num_threads(1);
  const pm::Batch one = pm::augmented_batch(views, idx, o, n, 5, 2);
  torch::set_num_threads(2);
  const pm::Batch two = pm::augmented_batch(views, idx, o, n, 5, 2);
  torch::set_num_threads(1);
  for (auto m : {&pm::Batch::image, &pm::Batch::normal, &pm::Batch::depth, &pm::Batch::color_lo, &pm::Batch::probes,
                 &pm::Batch::probe_mask, &pm::Batch::mask})
    EXPECT_TRUE(torch::equal(one.*m, two.*m));
  const pm::Batch other = pm::augmented_batch(views, idx, o, n, 6, 2);
  EXPECT_FALSE(torch::equal(one.image, other.image));
  pm::AugmentOptions off;
  off.enabled = false;
  EXPECT_TRUE(torch::equal(pm::augmented_batch(views, idx, off, n, 5, 2).image,
                           pm::collate({views[2], views[0], views[3]}).image));
}

}  // namespace
