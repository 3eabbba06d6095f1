// evaluate_view on synthetic views: a perfect prediction scores perfectly, resolutions are
// handled as documented, relighting is linear in the light and wired to Table 10's materials
// (a mirror sphere's centre under a white environment shows its base colour), bad prediction
// folders are reported naming the file.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include <unistd.h>

#include "phyir/core/error.h"
#include "phyir/core/image_io.h"
#include "phyir/core/pcg32.h"
#include "phyir/core/progress.h"
#include "phyir/eval/baselines.h"
#include "phyir/eval/evaluate_view.h"
#include "phyir/eval/pixel_metrics.h"
#include "phyir/core/image_resample.h"
#include "phyir/eval/views.h"

namespace phyir::eval {
namespace {

namespace fs = std::filesystem;

Image random_image(int w, int h, int c, float lo, float hi, uint64_t seed) {
  Pcg32 rng(seed, 3);
  Image im(w, h, c);
  for (float& v : im.pixels) v = rng.uniform(lo, hi);
  return im;
}

// A 16x8 view with random maps, a few invalid pixels and a 4x8 grid of 4x8 probes.
GroundTruthView synthetic_view() {
  GroundTruthView v;
  v.id = "room_0/v000";
  v.scene = "room_0";
  const int w = 16, h = 8;
  v.color = random_image(w, h, 3, 0, 2, 1);
  v.input = random_image(w, h, 3, 0, 1, 2);
  v.depth = random_image(w, h, 1, 0.5f, 5, 3);
  v.normal = random_image(w, h, 3, -1, 1, 4);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      float s = 0;
      for (int c = 0; c < 3; ++c) s += v.normal.at(x, y, c) * v.normal.at(x, y, c);
      for (int c = 0; c < 3; ++c) v.normal.at(x, y, c) /= std::sqrt(s);
    }
  v.basecolor = random_image(w, h, 3, 0, 1, 5);
  v.roughness = random_image(w, h, 1, 0, 1, 6);
  v.metalness = random_image(w, h, 1, 0, 1, 7);
  v.valid = Image(w, h, 1, 1.0f);
  v.valid.at(3, 2) = v.valid.at(10, 5) = 0.0f;
  view::ProbeMosaic p;
  p.layout = {4, 8, 4, 8};
  p.radiance = random_image(64, 16, 3, 0.1f, 3, 8);
  p.mask = Image(8, 4, 1, 1.0f);
  p.mask.at(0, 0) = 0.0f;
  v.probes = p;
  return v;
}

Prediction perfect(const GroundTruthView& v) {
  Prediction p;
  p.depth = v.depth, p.normal = v.normal, p.basecolor = v.basecolor, p.roughness = v.roughness;
  p.metalness = v.metalness, p.rerender = v.color, p.probes = v.probes;
  return p;
}

// Each pixel repeated into a k x k block: area-averaging it back gives the original exactly.
Image upsampled(const Image& im, int k) {
  Image out(im.width * k, im.height * k, im.channels);
  for (int y = 0; y < out.height; ++y)
    for (int x = 0; x < out.width; ++x)
      for (int c = 0; c < im.channels; ++c) out.at(x, y, c) = im.at(x / k, y / k, c);
  return out;
}

EvalSettings cheap() {
  EvalSettings s;
  s.relight_positions = 2;
  s.sphere.size = 16;
  s.sphere.spp = 4;
  return s;
}

TEST(EvaluateView, PerfectPredictionScoresPerfectly) {
  Progress::set_enabled(false);
  const GroundTruthView v = synthetic_view();
  const Metrics m = evaluate_view(v, perfect(v), cheap());
  for (const char* k : {"basecolor_mse", "roughness_mse", "metalness_mse", "rerender_mse", "depth_mae", "depth_abs_rel",
                        "depth_rmse", "depth_rmse_log", "depth_log10"})
    EXPECT_EQ(m.at(k), 0.0) << k;
  EXPECT_LT(m.at("normal_deg"), 0.05);  // acos near 1 in float
  EXPECT_EQ(m.at("depth_delta1"), 1.0);
  EXPECT_NEAR(m.at("probe_ssim"), 1.0, 1e-12);
  EXPECT_EQ(m.at("probes_compared"), 31.0);
  EXPECT_EQ(m.at("pixels_maps"), 16.0 * 8 - 2);
  EXPECT_EQ(m.at("relight_positions"), 2.0);
  for (const char* k : {"relight_diffuse_mae", "relight_matte_silver_rmse", "relight_mirror_silver_mae"})
    EXPECT_EQ(m.at(k), 0.0) << k;  // same probe, same seed: the same image
}

TEST(EvaluateView, AFinerPredictionIsAreaAveragedOntoTheGroundTruth) {
  const GroundTruthView v = synthetic_view();
  Prediction p = perfect(v);
  p.depth = upsampled(v.depth, 2), p.normal = upsampled(v.normal, 2), p.basecolor = upsampled(v.basecolor, 2);
  p.roughness = upsampled(v.roughness, 2), p.metalness = upsampled(v.metalness, 2);
  EvalSettings s = cheap();
  s.relight = false;
  const Metrics m = evaluate_view(v, p, s);
  EXPECT_NEAR(m.at("basecolor_mse"), 0.0, 1e-12);
  EXPECT_NEAR(m.at("depth_abs_rel"), 0.0, 1e-7);
  EXPECT_EQ(m.at("pixels_maps"), 16.0 * 8 - 2);
  // A coarser prediction: the ground truth is area-averaged onto it and a coarse pixel
  // counts only when all four of its fine pixels are valid (2 of 32 are not).
  Prediction coarse = perfect(v);
  coarse.basecolor = area_resize(v.basecolor, 8, 4);
  coarse.depth = area_resize(v.depth, 8, 4);
  coarse.normal.reset(), coarse.roughness.reset(), coarse.metalness.reset();
  const Metrics c = evaluate_view(v, coarse, s);
  EXPECT_NEAR(c.at("basecolor_mse"), 0.0, 1e-12);
  EXPECT_EQ(c.at("pixels_maps"), 30.0);
  EXPECT_TRUE(std::isnan(c.at("roughness_mse")));
}

TEST(EvaluateView, MetricsSeeADifference) {
  const GroundTruthView v = synthetic_view();
  Prediction p = perfect(v);
  for (float& x : p.basecolor->pixels) x += 0.1f;
  for (float& x : p.depth->pixels) x *= 1.3f;  // outside delta1, inside delta2
  const Metrics m = evaluate_view(v, p, cheap());
  EXPECT_NEAR(m.at("basecolor_mse"), 0.01, 1e-6);
  EXPECT_NEAR(m.at("depth_abs_rel"), 0.3, 1e-6);
  EXPECT_EQ(m.at("depth_delta1"), 0.0);
  EXPECT_EQ(m.at("depth_delta2"), 1.0);
}

// --radiance input: every radiance metric is that of both sides times 2^exposure_stops
// (MSE by its square, relighting errors linearly, probe SSIM on the scaled probes); the maps
// do not move.
TEST(EvaluateView, InputUnitsScaleTheRadianceMetricsByTheExposure) {
  GroundTruthView v = synthetic_view();
  v.exposure_stops = 2.0f;
  Prediction p = perfect(v);
  for (float& x : p.rerender->pixels) x += 0.1f;
  for (float& x : p.probes->radiance.pixels) x *= 1.5f;
  for (float& x : p.basecolor->pixels) x += 0.1f;
  EvalSettings absolute = cheap(), input = cheap();
  input.radiance_units = view::RadianceUnits::kInput;
  const Metrics a = evaluate_view(v, p, absolute), b = evaluate_view(v, p, input);
  EXPECT_NEAR(b.at("rerender_mse"), 16.0 * a.at("rerender_mse"), 1e-9 * b.at("rerender_mse"));
  EXPECT_NEAR(b.at("basecolor_mse"), a.at("basecolor_mse"), 1e-12);
  for (const char* k : {"relight_diffuse_mae", "relight_matte_silver_rmse", "relight_mirror_silver_mae"})
    EXPECT_NEAR(b.at(k), 4.0 * a.at(k), 1e-5 * b.at(k)) << k;
  const double ssim = probe_ssim(p.probes->scaled(4.0), v.probes->scaled(4.0)).ssim;
  EXPECT_NEAR(b.at("probe_ssim"), ssim, 1e-12);
  EXPECT_GT(std::abs(b.at("probe_ssim") - a.at("probe_ssim")), 1e-4);  // log(1 + L) is not scale-free
}

// The constant baseline in input units is the mean of the input-unit targets: handed over in
// the view's absolute unit, it scores as that mean against the view's input-unit target.
TEST(Baselines, ConstantMeanInInputUnitsIsTheMeanOfInputUnitTargets) {
  GroundTruthView v = synthetic_view();
  v.exposure_stops = 3.0f;
  BaselineStats stats;
  for (int c = 0; c < 3; ++c) stats.color[c] = 100.0, stats.input_color[c] = 0.5;
  stats.probe = Image(8, 4, 3, 100.0f);
  stats.input_probe = Image(8, 4, 3, 0.5f);
  const Prediction p = constant_mean_prediction(stats, v, view::RadianceUnits::kInput);
  EXPECT_FLOAT_EQ(p.rerender->at(0, 0, 0), 0.5f / 8.0f);
  EXPECT_FLOAT_EQ(p.probes->radiance.at(5, 3, 2), 0.5f / 8.0f);
  EvalSettings input = cheap();
  input.radiance_units = view::RadianceUnits::kInput;
  input.relight = false;
  Prediction expected = perfect(v);
  for (float& x : expected.rerender->pixels) x = 0.5f;
  GroundTruthView scaled = v;
  for (float& x : scaled.color.pixels) x *= 8.0f;
  scaled.exposure_stops = 0.0f;
  EXPECT_NEAR(evaluate_view(v, p, input).at("rerender_mse"), evaluate_view(scaled, expected, input).at("rerender_mse"),
              1e-9);
  EXPECT_FLOAT_EQ(constant_mean_prediction(stats, v).rerender->at(0, 0, 1), 100.0f);  // absolute: unchanged
}

TEST(Relight, ErrorIsLinearInTheLight) {
  // Twice the light gives twice the image (same seed, same paths), so the MAE between the two
  // is the mean of the dimmer image over the sphere.
  const Image probe = random_image(8, 4, 3, 0.2f, 2.0f, 41);
  Image twice = probe;
  for (float& x : twice.pixels) x *= 2.0f;
  RelightSettings s;
  s.size = 24;
  s.spp = 8;
  for (const SphereMaterial& mat : sphere_materials()) {
    const RelitSphere a = relight_sphere(probe, mat, s), b = relight_sphere(twice, mat, s);
    const Image zero(a.color.width, a.color.height, 3, 0.0f);
    EXPECT_NEAR(masked_mae(b.color, a.color, a.mask), masked_mae(a.color, zero, a.mask),
                1e-5 * masked_mae(a.color, zero, a.mask))
        << mat.key;
    EXPECT_GT(count_mask(a.mask), 24 * 24 / 2) << "the sphere fills most of the image";
  }
}

TEST(Relight, MirrorSphereCentreShowsItsBaseColourUnderAWhiteEnvironment) {
  // Facing the camera (n.v = 1) a metal's Fresnel reflectance is its base colour (F0) and the
  // mirror lobe reflects the environment (radiance 1) exactly; the diffuse sphere is black-free
  // and below 1 (albedo 0.5 plus a dielectric specular lobe of a few percent).
  const Image white(8, 4, 3, 1.0f);
  RelightSettings s;
  s.size = 65;  // odd: a pixel centre on the axis
  s.spp = 4;
  const SphereMaterial& mirror = sphere_materials()[2];
  const RelitSphere r = relight_sphere(white, mirror, s);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(r.color.at(32, 32, c), mirror.base_color[c], 2e-3) << c;
  const RelitSphere d = relight_sphere(white, sphere_materials()[0], RelightSettings{});
  const Image zero(d.color.width, d.color.height, 3, 0.0f);
  const double mean = masked_mae(d.color, zero, d.mask);
  EXPECT_GT(mean, 0.45);
  EXPECT_LT(mean, 0.62);
}

TEST(RelightPositions, SpreadEvenlyOverTheValidCells) {
  Image valid(4, 2, 1, 1.0f);
  valid.at(0, 0) = 0.0f;
  const auto p = relight_positions(valid, 2);  // 7 valid cells: picks index 1 and 5
  ASSERT_EQ(p.size(), 2u);
  EXPECT_EQ(p[0], std::make_pair(0, 2));
  EXPECT_EQ(p[1], std::make_pair(1, 2));
  EXPECT_EQ(relight_positions(valid, 20).size(), 7u);
  EXPECT_TRUE(relight_positions(Image(4, 2, 1, 0.0f), 2).empty());
}

TEST(LoadPrediction, MissingAndMismatchedFilesAreNamed) {
  const fs::path dir = fs::temp_directory_path() / ("phyir_eval_pred_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  for (const char* f : {"depth.exr", "roughness.exr", "metalness.exr"}) write_image(dir / f, Image(16, 8, 1, 1.0f));
  write_image(dir / "normal.exr", Image(16, 8, 3, 0.5f));
  try {
    load_prediction(dir);
    ADD_FAILURE() << "no error for a missing basecolor.exr";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("basecolor.exr: missing"), std::string::npos) << e.what();
  }
  write_image(dir / "basecolor.exr", Image(32, 16, 3, 0.5f));
  try {
    load_prediction(dir);
    ADD_FAILURE() << "no error for a basecolor.exr of another size";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("basecolor.exr: 32x16 does not match"), std::string::npos) << e.what();
  }
  write_image(dir / "basecolor.exr", Image(16, 8, 3, 0.5f));
  write_image(dir / "probes.exr", Image(64, 16, 3, 0.5f));
  try {
    load_prediction(dir);
    ADD_FAILURE() << "no error for probes.exr without probe_mask.exr";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("probe_mask.exr"), std::string::npos) << e.what();
  }
  write_image(dir / "probe_mask.exr", Image(5, 4, 1, 1.0f));  // 64 is not a multiple of 5
  EXPECT_THROW(load_prediction(dir), Error);
  write_image(dir / "probe_mask.exr", Image(8, 4, 1, 1.0f));
  const Prediction p = load_prediction(dir);
  EXPECT_EQ(p.probes->layout.res_height, 4);
  EXPECT_EQ(p.probes->layout.res_width, 8);
  ASSERT_EQ(p.missing.size(), 1u);
  EXPECT_EQ(p.missing[0], "rerender.exr");
  fs::remove_all(dir);
}

}  // namespace
}  // namespace phyir::eval
