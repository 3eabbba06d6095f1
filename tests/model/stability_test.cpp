// The network side of the stability matrix (issue 8; docs/robustness.md): the torch
// safe-math mirror equals core's constants and has finite gradients at its edges; the torch
// BRDF and the rendering layer give finite values AND finite gradients for the whole matrix
// (roughness {0, 1e-6, 1e-3, 0.05, 0.5, 1} x metalness {0, 0.5, 1} x base colour {0, 1},
// n.v and n.l from 1 to slightly negative, degenerate half vectors, probes of radiance 1e6).
#include <glm/glm.hpp>

#include "phyir/core/safe_math.h"
#include "render_layer.h"
#include "safe_math.h"

namespace {

namespace pm = phyir::model;
namespace sm = phyir::model::safe_math;

struct ThreadSetup {
  ThreadSetup() { torch::set_num_threads(1); }  // shared machines: no OpenMP spinning
} thread_setup;

const std::vector<double> kRoughness = {0.0, 1e-6, 1e-3, 0.05, 0.5, 1.0};
const std::vector<double> kMetalness = {0.0, 0.5, 1.0};
const std::vector<double> kBaseColor = {0.0, 1.0};
const std::vector<double> kCosines = {1.0, 0.7, 0.3, 0.1, 1e-2, 1e-3, 2e-4, 1e-4, 5e-5, 0.0, -1e-4, -1e-2};
const std::vector<double> kAzimuths = {0.0, 1.5707963267948966, 3.141592653589793};

bool all_finite(const torch::Tensor& t) { return t.defined() && torch::isfinite(t).all().item<bool>(); }

void report(const char* what, int64_t cases) {
  std::printf("[stability] %s: %lld cases\n", what, static_cast<long long>(cases));
  ::testing::Test::RecordProperty(what, std::to_string(cases));
}

// --- The safe-math mirror --------------------------------------------------------------------

TEST(ModelStability, SafeMathConstantsEqualCore) {
  EXPECT_EQ(sm::kMinCosine, static_cast<double>(phyir::kMinCosine));
  EXPECT_EQ(sm::kTinyDenominator, static_cast<double>(phyir::kTinyDenominator));
  EXPECT_EQ(sm::kMinLength2, static_cast<double>(phyir::kMinLength2));
  EXPECT_EQ(sm::kOneMinusEpsilon, static_cast<double>(phyir::kOneMinusEpsilon));
}

// Value and gradient of f at each x, in float and double.
template <typename F>
void expect_finite_value_and_gradient(const char* name, F f, const std::vector<double>& xs) {
  for (torch::Dtype dtype : {torch::kFloat, torch::kDouble}) {
    const torch::Tensor x = torch::tensor(xs, torch::TensorOptions().dtype(torch::kDouble)).to(dtype).requires_grad_(true);
    const torch::Tensor y = f(x);
    EXPECT_TRUE(all_finite(y)) << name << " values " << y;
    y.sum().backward();
    EXPECT_TRUE(all_finite(x.grad())) << name << " gradients " << x.grad();
  }
}

TEST(ModelStability, SafeMathHasFiniteValuesAndGradientsAtItsEdges) {
  const double tiny = sm::kTinyDenominator;
  expect_finite_value_and_gradient("safe_sqrt", [](const torch::Tensor& x) { return sm::safe_sqrt(x); },
                                   {-1.0, -1e-30, 0.0, 1e-30, tiny, 1e-10, 1.0, 1e30});
  expect_finite_value_and_gradient("safe_acos", [](const torch::Tensor& x) { return sm::safe_acos(x); },
                                   {-2.0, -1.0, -1.0 + 1e-9, 0.0, 1.0 - 1e-9, 1.0, 2.0});
  expect_finite_value_and_gradient("clamp01", [](const torch::Tensor& x) { return sm::clamp01(x); }, {-1.0, 0.0, 0.5, 1.0, 2.0});
  expect_finite_value_and_gradient(
      "safe_div (denominator)", [](const torch::Tensor& b) { return sm::safe_div(torch::ones_like(b), b); },
      {0.0, 1e-30, -1e-30, tiny, 1e-19, -1.0, 1.0});
  expect_finite_value_and_gradient(
      "safe_normalize", [](const torch::Tensor& x) {
        return sm::safe_normalize(x.view({-1, 3}), torch::tensor({0.0, 0.0, 1.0}));
      },
      {0.0, 0.0, 0.0, 1e-20, 0.0, 0.0, 1e-14, 1e-14, 0.0, 1.0, 2.0, 3.0});
  // Values: the same answers as core's functions.
  const torch::Tensor d = torch::tensor({0.0, 1e-30, 4.0}, torch::kFloat);
  EXPECT_TRUE(torch::allclose(sm::safe_div(torch::ones_like(d), d), torch::tensor({0.0f, 0.0f, 0.25f})));
  EXPECT_FLOAT_EQ(sm::safe_sqrt(torch::tensor({4.0f})).item<float>(), phyir::safe_sqrt(4.0f));
  EXPECT_NEAR(sm::safe_acos(torch::tensor({0.3f})).item<float>(), phyir::safe_acos(0.3f), 1e-6);
  const torch::Tensor n = sm::safe_normalize(torch::tensor({{0.0f, 0.0f, 0.0f}, {3.0f, 0.0f, 4.0f}}), torch::tensor({0.0f, 1.0f, 0.0f}));
  EXPECT_TRUE(torch::allclose(n, torch::tensor({{0.0f, 1.0f, 0.0f}, {0.6f, 0.0f, 0.8f}})));
  report("model safe-math edge values (5 functions x 2 dtypes)", 2 * (8 + 7 + 5 + 7 + 4));
}

// --- The torch BRDF -------------------------------------------------------------------------

// Every (material, n.v, n.l, azimuth) as rows, plus the degenerate pairs wo = wi and wo = -wi.
struct BrdfRows {
  torch::Tensor base, rough, metal, wo, wi;
};

BrdfRows brdf_rows() {
  std::vector<float> b, r, m, wo, wi;
  auto dir = [](double c, double phi, std::vector<float>& out) {
    const double s = std::sqrt(std::max(0.0, 1.0 - c * c));
    out.insert(out.end(), {float(s * std::cos(phi)), float(s * std::sin(phi)), float(c)});
  };
  for (double R : kRoughness)
    for (double M : kMetalness)
      for (double B : kBaseColor) {
        auto material = [&] {
          b.insert(b.end(), {float(B), float(B), float(B)});
          r.push_back(float(R));
          m.push_back(float(M));
        };
        for (double cv : kCosines)
          for (double cl : kCosines)
            for (double phi : kAzimuths) {
              material();
              dir(cv, 0.0, wo);
              dir(cl, phi, wi);
            }
        for (double c : kCosines) {  // wo = wi and wo = -wi
          material();
          dir(c, 0.4, wo);
          dir(c, 0.4, wi);
          material();
          dir(c, 0.4, wo);
          dir(c, 0.4, wi);
          for (int k = 0; k < 3; ++k) wi[wi.size() - 1 - k] = -wi[wi.size() - 1 - k];
        }
      }
  const int64_t n = static_cast<int64_t>(r.size());
  auto t = [n](const std::vector<float>& v, int64_t c) { return torch::tensor(v).view({n, c}); };
  return {t(b, 3), t(r, 1), t(m, 1), t(wo, 3), t(wi, 3)};
}

TEST(ModelStability, BrdfEvalHasFiniteValuesAndGradientsForTheWholeMatrix) {
  BrdfRows rows = brdf_rows();
  for (torch::Tensor* t : {&rows.base, &rows.rough, &rows.metal, &rows.wo, &rows.wi}) t->requires_grad_(true);
  const torch::Tensor f = pm::brdf_eval(rows.base, rows.rough, rows.metal, rows.wo, rows.wi);
  ASSERT_TRUE(all_finite(f));
  EXPECT_GE(f.min().item<float>(), 0.0f);
  // Below kMinCosine on either side: exactly zero.
  const torch::Tensor below = (rows.wo.select(-1, 2) < sm::kMinCosine) | (rows.wi.select(-1, 2) < sm::kMinCosine);
  EXPECT_EQ(f.detach().index({below}).abs().max().item<float>(), 0.0f);
  f.sum().backward();
  int64_t bad = 0;
  for (const auto& [name, t] : {std::make_pair("base colour", rows.base), std::make_pair("roughness", rows.rough),
                                std::make_pair("metalness", rows.metal), std::make_pair("wo", rows.wo),
                                std::make_pair("wi", rows.wi)}) {
    const torch::Tensor nonfinite = ~torch::isfinite(t.grad()).all(-1);
    bad += nonfinite.sum().item<int64_t>();
    if (nonfinite.any().item<bool>()) {
      const int64_t i = nonfinite.nonzero()[0][0].item<int64_t>();
      ADD_FAILURE() << "non-finite gradient of " << name << " at row " << i << ": R=" << rows.rough[i].item<float>()
                    << " M=" << rows.metal[i].item<float>() << " B=" << rows.base[i][0].item<float>() << " wo=" << rows.wo[i]
                    << " wi=" << rows.wi[i];
    }
  }
  EXPECT_EQ(bad, 0);
  report("model BRDF eval rows (value + 5 gradients)", rows.rough.size(0));
}

// --- The rendering layer --------------------------------------------------------------------

// Maps [B,C,H,W] for a batch in which batch element k has n.v = kCosines[k] at every pixel
// and the 36 materials are spread over a 6 x 6 panorama. Probes hold 0 except one bright
// texel of radiance 1e6 per probe (a tiny, very bright light) and 1e-30 elsewhere in half of
// them (nearly black, but not zero).
struct LayerInputs {
  torch::Tensor normal, base, rough, metal, probes;
};

LayerInputs layer_inputs() {
  const int64_t Bn = static_cast<int64_t>(kCosines.size()), H = 6, W = 6, h = 4, w = 8;
  const auto opts = torch::TensorOptions().dtype(torch::kFloat);
  const torch::Tensor v = -pm::pixel_directions(H, W, opts);  // [H,W,3] towards the camera
  const torch::Tensor up = torch::tensor({0.0f, 1.0f, 0.0f}).expand({H, W, 3});
  torch::Tensor t = torch::cross(v, up, -1);
  t = t / t.norm(2, -1, true);  // no pixel of a 6-row panorama is at a pole
  std::vector<torch::Tensor> normals;
  for (double c : kCosines)
    normals.push_back((c * v + std::sqrt(std::max(0.0, 1.0 - c * c)) * t).permute({2, 0, 1}));
  LayerInputs in;
  in.normal = torch::stack(normals);  // [Bn,3,H,W]
  std::vector<float> B, R, M;
  for (double r : kRoughness)
    for (double m : kMetalness)
      for (double b : kBaseColor) {
        B.push_back(float(b));
        R.push_back(float(r));
        M.push_back(float(m));
      }
  in.base = torch::tensor(B).view({1, 1, H, W}).expand({Bn, 3, H, W}).contiguous();
  in.rough = torch::tensor(R).view({1, 1, H, W}).expand({Bn, 1, H, W}).contiguous();
  in.metal = torch::tensor(M).view({1, 1, H, W}).expand({Bn, 1, H, W}).contiguous();
  in.probes = torch::zeros({Bn, H, W, h, w, 3}, opts);
  in.probes.index_put_({torch::indexing::Slice(), torch::indexing::Slice(), torch::indexing::Slice(0, W, 2)}, 1e-30f);
  in.probes.index_put_({torch::indexing::Slice(), torch::indexing::Slice(), torch::indexing::Slice(), 1, 3}, 1e6f);
  return in;
}

TEST(ModelStability, RenderingLayerHasFiniteValuesAndGradientsForTheWholeMatrix) {
  LayerInputs in = layer_inputs();
  for (torch::Tensor* t : {&in.normal, &in.base, &in.rough, &in.metal, &in.probes}) t->requires_grad_(true);
  pm::RenderSettings settings;
  settings.diffuse_samples = 16;
  settings.specular_samples = 16;
  torch::manual_seed(8);
  const pm::RenderOutput out = pm::render_layer(in.normal, in.base, in.rough, in.metal, in.probes, settings);
  ASSERT_TRUE(all_finite(out.image));
  EXPECT_GE(out.image.min().item<float>(), 0.0f);
  // A surface seen from below its shading normal (n.v < kMinCosine) renders black.
  for (size_t k = 0; k < kCosines.size(); ++k) {
    if (kCosines[k] < sm::kMinCosine) {
      EXPECT_EQ(out.image[k].abs().max().item<float>(), 0.0f) << "n.v " << kCosines[k];
    }
  }
  // Sum with weights that keep the 1e6 texel from dominating the float sum.
  (out.image / 1e6).sum().backward();
  for (const auto& [name, t] : {std::make_pair("normal", in.normal), std::make_pair("base colour", in.base),
                                std::make_pair("roughness", in.rough), std::make_pair("metalness", in.metal),
                                std::make_pair("probes", in.probes)})
    EXPECT_TRUE(all_finite(t.grad())) << "non-finite gradient of " << name;
  report("model rendering layer pixels (12 n.v x 36 materials, value + 5 gradients)", in.rough.numel());
}

TEST(ModelStability, RenderingLayerDegenerateNormalsAndProbes) {
  // Zero-length, NaN-free but tiny, and non-unit normals; all-zero and all-1e6 probes.
  LayerInputs in = layer_inputs();
  in.normal = in.normal.clone();
  in.normal[0].zero_();
  in.normal[1].mul_(1e-20f);
  in.normal[2].mul_(1e6f);
  in.probes = in.probes.clone();
  in.probes[3].zero_();
  in.probes[4].fill_(1e6f);
  for (torch::Tensor* t : {&in.normal, &in.base, &in.rough, &in.metal, &in.probes}) t->requires_grad_(true);
  pm::RenderSettings settings;
  settings.diffuse_samples = 8;
  settings.specular_samples = 8;
  torch::manual_seed(9);
  const pm::RenderOutput out = pm::render_layer(in.normal, in.base, in.rough, in.metal, in.probes, settings);
  ASSERT_TRUE(all_finite(out.image));
  (out.image / 1e6).sum().backward();
  for (const auto& [name, t] : {std::make_pair("normal", in.normal), std::make_pair("base colour", in.base),
                                std::make_pair("roughness", in.rough), std::make_pair("metalness", in.metal),
                                std::make_pair("probes", in.probes)})
    EXPECT_TRUE(all_finite(t.grad())) << "non-finite gradient of " << name;
  report("model rendering layer degenerate normals/probes (batches)", 5);
}

}  // namespace
