// Rendering probes to an error target (probe_error_target.h, --probe-error): the passes'
// merge, the choice of probes, and on a lit room that the target is reached, that the error
// against a converged reference falls with it, and that the output is the same whatever the
// thread count.
#include <gtest/gtest.h>

#include <tbb/global_control.h>

#include <cmath>
#include <random>

#include <fmt/format.h>
#include <cstdio>
#include <vector>

#include "phyir/core/image_error.h"
#include "phyir/core/setting_error.h"
#include "phyir/render/probe_renderer.h"
#include "probe_error_target.h"
#include "probe_pass_schedule.h"
#include "sanitizer_skip.h"
#include "single_probe.h"
#include "test_scenes.h"

namespace phyir::render {
namespace {

// A 1 x n grid of 2x4-texel valid probes, every texel of probe p at value[p] with sigma[p].
ProbeOutput constant_probes(const std::vector<float>& value, const std::vector<float>& sigma) {
  ProbeOutput out;
  out.layout = {1, int(value.size()), 2, 4};
  for (size_t p = 0; p < value.size(); ++p) out.sites.push_back(single_site(glm::vec3(float(p), 1.0f, 0.0f)).front());
  out.mosaic = Image(out.layout.mosaic_width(), out.layout.mosaic_height(), 3);
  out.standard_error = Image(out.layout.mosaic_width(), out.layout.mosaic_height(), 1);
  for (int p = 0; p < int(value.size()); ++p)
    for (int t = 0; t < out.layout.texels_per_probe(); ++t) {
      const glm::ivec2 at = out.layout.mosaic_pixel(p, t);
      for (int c = 0; c < 3; ++c) out.mosaic.at(at.x, at.y, c) = value[size_t(p)];
      out.standard_error.at(at.x, at.y, 0) = sigma[size_t(p)];
    }
  return out;
}

float texel(const ProbeOutput& out, int p, int c = 0) {
  const glm::ivec2 at = out.layout.mosaic_pixel(p, 0);
  return out.mosaic.at(at.x, at.y, c);
}

float sigma_of(const ProbeOutput& out, int p) {
  const glm::ivec2 at = out.layout.mosaic_pixel(p, 0);
  return out.standard_error.at(at.x, at.y, 0);
}

TEST(ProbeErrorTarget, EstimatedErrorIsRmsSigmaOverMeanLuminance) {
  const ProbeOutput out = constant_probes({1.0f, 3.0f}, {0.3f, 0.4f});
  std::vector<int> passes = first_passes(out, {});
  EXPECT_NEAR(estimated_grid_error(out, passes).relative(), std::sqrt((0.09 + 0.16) / 2.0) / 2.0, 1e-6);
  // A probe holding no pass (not rendered) is not counted.
  passes[1] = 0;
  EXPECT_NEAR(estimated_grid_error(out, passes).relative(), 0.3, 1e-6);
  EXPECT_EQ(first_passes(out, {1}), (std::vector<int>{0, 1}));
}

TEST(ProbeErrorTarget, MergeIsTheEqualWeightMeanOfThePasses) {
  ProbeOutput total = constant_probes({1.0f, 2.0f}, {0.4f, 0.2f});
  const ProbeOutput pass = constant_probes({4.0f, 100.0f}, {0.2f, 9.0f});
  std::vector<int> passes{2, 1};
  merge_pass(pass, {0}, &passes, &total);
  EXPECT_NEAR(texel(total, 0), (2.0 * 1.0 + 4.0) / 3.0, 1e-6);  // two passes held, one added
  EXPECT_NEAR(sigma_of(total, 0), std::sqrt(4.0 * 0.16 + 0.04) / 3.0, 1e-6);
  EXPECT_EQ(texel(total, 1), 2.0f);  // not refined: untouched
  EXPECT_EQ(passes, (std::vector<int>{3, 1}));
}

// With the directions behind each texel, each pass weighs by them: 4 held, 24 added.
TEST(ProbeErrorTarget, MergeWeighsEachPassByItsDirections) {
  ProbeOutput total = constant_probes({1.0f, 2.0f}, {0.4f, 0.2f});
  ProbeOutput pass = constant_probes({4.0f, 100.0f}, {0.2f, 9.0f});
  total.texel_samples.assign(16, 4.0f);
  pass.texel_samples.assign(16, 24.0f);
  std::vector<int> passes{1, 1};
  merge_pass(pass, {0}, &passes, &total);
  EXPECT_NEAR(texel(total, 0), (4.0 * 1.0 + 24.0 * 4.0) / 28.0, 1e-6);
  EXPECT_NEAR(sigma_of(total, 0), std::sqrt(16.0 * 0.16 + 576.0 * 0.04) / 28.0, 1e-6);
  EXPECT_EQ(total.texel_samples[0], 28.0f);
  EXPECT_EQ(total.texel_samples[8], 4.0f);  // probe 1, not refined
  EXPECT_EQ(texel(total, 1), 2.0f);
}

TEST(ProbeErrorTarget, RefinesTheProbesHoldingTheVariance) {
  const ProbeOutput out = constant_probes({1.0f, 1.0f, 1.0f}, {0.05f, 0.5f, 0.01f});
  const std::vector<int> passes = first_passes(out, {});
  // Mean sigma^2 0.0842 -> relative 0.29; refining the noisy probe once takes its variance
  // to half: relative 0.21.
  EXPECT_EQ(probes_to_refine(out, passes, 0.22), (std::vector<int>{1}));
  EXPECT_EQ(probes_to_refine(out, passes, 0.0001), (std::vector<int>{0, 1, 2}));  // out of reach: all
  EXPECT_TRUE(probes_to_refine(out, passes, 0.5).empty());
  std::vector<int> full(3, kMaxErrorPasses);
  EXPECT_TRUE(probes_to_refine(out, full, 0.0001).empty());  // no probe may take another pass
}

TEST(ProbeErrorTarget, AgreementIsThePassesDifferencesOverTheirReportedVariances) {
  ProbeOutput total = constant_probes({1.0f, 2.0f}, {0.1f, 0.2f});
  const ProbeOutput pass = constant_probes({1.3f, 2.0f}, {0.1f, 0.2f});
  std::vector<int> passes{1, 1};
  PassAgreement agreement;
  EXPECT_EQ(agreement.factor(), 1.0);  // no two passes met yet
  merge_pass(pass, {0, 1}, &passes, &total, &agreement);
  EXPECT_EQ(agreement.texels, 16u);
  // 8 texels differ by 0.3, 8 agree; reported 8 x (0.01 + 0.01) + 8 x (0.04 + 0.04).
  EXPECT_NEAR(agreement.factor(), 8.0 * 0.09 / 0.8, 1e-5);
  EXPECT_NEAR(estimated_grid_error(total, passes, 4.0).relative(), 2.0 * estimated_grid_error(total, passes).relative(),
              1e-9);
}

TEST(ProbeErrorTarget, ChecksOneValidProbeInEightOfALargeGrid) {
  std::vector<int> passes(400, 1);
  passes[0] = 0;  // not valid
  const std::vector<int> check = probes_to_check(passes);
  ASSERT_EQ(check.size(), 50u);
  EXPECT_EQ(check[0], 1);
  EXPECT_EQ(check[1], 9);
  std::vector<int> few(100, 1);  // fewer than kCheckEvery x kMinCheckProbes: all of them
  EXPECT_EQ(probes_to_check(few).size(), 100u);
}

// Passes whose texels are 1 plus Gaussian noise of sd 0.2 but report sigma 0.1, as a texel
// that missed a bright part reports too little: the target must follow the true noise.
ProbeOutput noisy_pass(const ProbeSettings& settings, const std::vector<int>& subset) {
  std::vector<float> value(200, 1.0f), sigma(200, 0.1f);
  ProbeOutput out = constant_probes(value, sigma);
  std::mt19937_64 rng(settings.seed);
  std::normal_distribution<float> noise(0.0f, 0.2f);
  for (int p = 0; p < 200; ++p)
    for (int t = 0; t < out.layout.texels_per_probe(); ++t) {
      const glm::ivec2 at = out.layout.mosaic_pixel(p, t);
      const float v = 1.0f + noise(rng);
      for (int c = 0; c < 3; ++c) out.mosaic.at(at.x, at.y, c) = v;
    }
  (void)subset;
  return out;
}

TEST(ProbeErrorTarget, ATargetFollowsTheNoiseThePassesShowNotTheSigmaTheyReport) {
  ProbeSettings settings;
  settings.target_error = 0.1f;  // what sigma alone says the first pass has reached
  ProbeOutput out = noisy_pass(settings, {});
  refine_to_error(settings, {}, [](const ProbeSettings& s, const std::vector<int>& subset,
                                   const std::vector<uint8_t>&) { return noisy_pass(s, subset); }, &out);
  EXPECT_NEAR(out.stats.error.sigma_factor, 2.0, 0.2);
  EXPECT_GE(out.stats.error.passes, 4);  // 0.2 / sqrt(passes) <= 0.1
  EXPECT_LE(out.stats.error.estimated, 0.1 + 1e-6);
  double squared = 0.0;
  for (int p = 0; p < 200; ++p) squared += double(texel(out, p) - 1.0f) * double(texel(out, p) - 1.0f);
  EXPECT_LT(std::sqrt(squared / 200.0), 0.12);  // the true error reached the target too
}

// The check renders one probe in 8 as the first pass did (its kernels, a first look of its
// own); the passes after it take the earlier choices and shrink their kernels.
TEST(ProbeErrorTarget, TheCheckIsAReplicaOfTheFirstPass) {
  ProbeSettings settings;
  settings.target_error = 0.1f;
  ProbeOutput out = noisy_pass(settings, {});
  out.texel_choices.assign(200 * 8, kHardTexel);
  struct Call {
    size_t probes;
    bool choices, progressive_kernels;
  };
  std::vector<Call> calls;
  const ProbeSettings first_pass_kernels = pass_settings(settings, 0);
  refine_to_error(settings, {},
                  [&](const ProbeSettings& s, const std::vector<int>& subset, const std::vector<uint8_t>& choices) {
                    calls.push_back({subset.size(), !choices.empty(),
                                     s.cache.cell_size != first_pass_kernels.cache.cell_size});
                    return noisy_pass(s, subset);
                  },
                  &out);
  ASSERT_GE(calls.size(), 2u);
  EXPECT_EQ(calls[0].probes, 25u);
  EXPECT_FALSE(calls[0].choices);
  EXPECT_FALSE(calls[0].progressive_kernels);
  EXPECT_TRUE(calls[1].choices);
  EXPECT_TRUE(calls[1].progressive_kernels);
}

TEST(ProbeErrorTarget, LaterPassesShrinkTheReuseKernels) {
  ProbeSettings base;
  EXPECT_EQ(pass_settings(base, 0).seed, base.seed);
  const ProbeSettings eighth = pass_settings(base, 7);  // (7 + 1)^(-1/3) = 1/2
  EXPECT_NE(eighth.seed, base.seed);
  EXPECT_NE(pass_settings(base, 6).seed, eighth.seed);
  EXPECT_NEAR(eighth.cache.cell_size, 0.5f * base.cache.cell_size, 1e-6f);
  EXPECT_NEAR(eighth.cache.direct_distance_cells * eighth.cache.cell_size,
              base.cache.direct_distance_cells * base.cache.cell_size, 1e-5f);  // the same metres
  EXPECT_NEAR(eighth.sharing.parallax_texels, 0.5f * base.sharing.parallax_texels, 1e-6f);
  EXPECT_EQ(eighth.spp, base.spp);
  EXPECT_EQ(pass_settings(base, 0).chain_end_paths, 0.0f);
  EXPECT_NEAR(eighth.chain_end_paths, 0.75f, 1e-6f);
  base.progressive = false;
  const ProbeSettings fixed = pass_settings(base, 7);
  EXPECT_EQ(fixed.cache.cell_size, base.cache.cell_size);
  EXPECT_EQ(fixed.sharing.parallax_texels, base.sharing.parallax_texels);
  EXPECT_EQ(fixed.chain_end_paths, 0.0f);
  EXPECT_EQ(fixed.seed, eighth.seed);
}

scenes::Scene lit_room() {
  scenes::Scene scene = test::make_box_room(glm::vec3(-2.0f, 0.0f, -2.0f), glm::vec3(2.0f, 3.0f, 2.0f),
                                            test::make_material(glm::vec3(0.7f, 0.6f, 0.5f), 0.8f));
  const int light = test::add_material(scene, test::make_emitter(glm::vec3(6.0f)));
  test::add_box(scene, glm::vec3(0.6f, 0.0f, -0.4f), glm::vec3(1.2f, 0.8f, 0.4f), 0);
  test::add_quad(scene, glm::vec3(-0.5f, 2.99f, -0.5f), glm::vec3(1, 0, 0), glm::vec3(0, 0, 1), light, "light");
  return scene;
}

std::vector<ProbeSite> row_of_sites() {
  std::vector<ProbeSite> out;
  for (int k = 0; k < 4; ++k) out.push_back(single_site(glm::vec3(-1.5f + 0.9f * float(k), 0.3f, 0.5f)).front());
  return out;
}

ProbeOutput render_path(const RenderScene& rs, const Effects& effects, int spp, float target) {
  ProbeSettings s = settings_for(ProbeMode::kPath, spp, 4, 8, 4);
  s.layout.grid_width = 4;
  s.target_error = target;
  return ProbeRenderer(rs, effects, s).render_at(row_of_sites());
}

TEST(ProbeErrorTarget, ReachesTheTargetAndTheErrorFallsWithIt) {
  PHYIR_SKIP_UNDER_SANITIZERS("ProbeErrorTarget.SameOutputWhateverTheThreadCount and the merge and choice tests");
  const scenes::Scene scene = lit_room();
  const RenderScene rs(scene);
  const Effects effects = analyse_effects(scene, false);
  const ProbeOutput reference = render_path(rs, effects, 4096, 0.0f);
  const ProbeOutput once = render_path(rs, effects, 8, 0.0f);
  const ProbeOutput targeted = render_path(rs, effects, 8, 0.5f * float(once.stats.error.estimated));
  EXPECT_GT(targeted.stats.error.passes, 2);
  EXPECT_LE(targeted.stats.error.estimated, 0.5 * once.stats.error.estimated + 1e-9);
  const double before = image_error(once.mosaic, reference.mosaic).relative_rmse;
  const double after = image_error(targeted.mosaic, reference.mosaic).relative_rmse;
  EXPECT_LT(after, 0.65 * before) << before << " -> " << after;
}

TEST(ProbeErrorTarget, SameOutputWhateverTheThreadCount) {
  const scenes::Scene scene = lit_room();
  const RenderScene rs(scene);
  const Effects effects = analyse_effects(scene, false);
  ProbeSettings s = settings_for(ProbeMode::kCache, 2, 4, 8, 4);
  s.layout.grid_width = 4;
  s.target_error = 0.02f;
  ProbeOutput one, two;
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
    one = ProbeRenderer(rs, effects, s).render_at(row_of_sites());
  }
  two = ProbeRenderer(rs, effects, s).render_at(row_of_sites());
  EXPECT_GT(one.stats.error.passes, 1);
  EXPECT_EQ(one.mosaic.pixels, two.mosaic.pixels);
  EXPECT_EQ(one.standard_error.pixels, two.standard_error.pixels);
}

// A sharp shadow in cached direct light: a 2 cm bar 1.5 m under a 3 cm ceiling light casts a
// shadow a few centimetres wide on the floor, which 5 cm cells blur. A probe 30 cm above it.
scenes::Scene shadow_room() {
  scenes::Scene scene = test::make_box_room(glm::vec3(-2.0f, 0.0f, -2.0f), glm::vec3(2.0f, 3.0f, 2.0f),
                                            test::make_material(glm::vec3(0.5f), 1.0f));
  const int light = test::add_material(scene, test::make_emitter(glm::vec3(3000.0f)));
  test::add_box(scene, glm::vec3(-1.0f, 1.49f, -0.01f), glm::vec3(1.0f, 1.51f, 0.01f), 0);
  test::add_quad(scene, glm::vec3(-0.015f, 2.95f, -0.015f), glm::vec3(0.03f, 0, 0), glm::vec3(0, 0, 0.03f), light,
                 "light");
  return scene;
}

// A rough metal wall whose lobe sees a polished floor that mirrors a ceiling light: where the
// wall's specular rays end (the floor, path regularisation), the cache lights the floor's
// lobe uniformly, which misses the light's image.
scenes::Scene mirror_room() {
  scenes::Scene scene = test::make_box_room(glm::vec3(-2.0f, 0.0f, -2.0f), glm::vec3(2.0f, 3.0f, 2.0f),
                                            test::make_material(glm::vec3(0.5f), 1.0f));
  const int rough_metal = test::add_material(scene, test::make_material(glm::vec3(0.9f), 0.4f, 1.0f));
  const int mirror = test::add_material(scene, test::make_material(glm::vec3(0.9f), 0.05f, 1.0f));
  const int light = test::add_material(scene, test::make_emitter(glm::vec3(10.0f)));
  test::add_quad(scene, glm::vec3(-1.9f, 0.001f, -1.9f), glm::vec3(0, 0, 3.8f), glm::vec3(3.8f, 0, 0), mirror, "mirror floor");
  test::add_quad(scene, glm::vec3(1.99f, 0.0f, -1.9f), glm::vec3(0, 0, 3.8f), glm::vec3(0, 2.9f, 0), rough_metal,
                 "rough metal wall");
  test::add_quad(scene, glm::vec3(-0.6f, 2.95f, -0.6f), glm::vec3(1.2f, 0, 0), glm::vec3(0, 0, 1.2f), light, "light");
  return scene;
}

struct PassErrors {
  double once = 0.0, fixed = 0.0, progressive = 0.0;
};

// The error of the light the room reflects at one probe (the texels at or above `light_seen`,
// the light's own and its mirror images, the same in every mode, left out) against a converged reference: one pass, 16 passes with the first's
// kernels, 16 progressive passes.
PassErrors pass_errors(const scenes::Scene& scene, const glm::vec3& origin, float light_seen) {
  const RenderScene rs(scene);
  const Effects effects = analyse_effects(scene, false);
  const std::vector<ProbeSite> site = single_site(origin);
  const ProbeOutput reference = ProbeRenderer(rs, effects, settings_for(ProbeMode::kPath, 2048, 16, 32, 3)).render_at(site);
  Image reflected(reference.mosaic.width, reference.mosaic.height, 1);
  for (int y = 0; y < reflected.height; ++y)
    for (int x = 0; x < reflected.width; ++x) reflected.at(x, y) = reference.mosaic.at(x, y, 0) < light_seen ? 1.0f : 0.0f;
  ProbeSettings s = settings_for(ProbeMode::kCache, 16, 16, 32, 3);
  s.cache.samples_per_cell = 256;
  s.balance = 0.0f;  // the kernels alone: balancing takes much of the mirror's noise in every mode
  auto error = [&](float target, bool progressive) {
    s.target_error = target;
    s.progressive = progressive;
    const ProbeOutput out = ProbeRenderer(rs, effects, s).render_at(site);
    if (target > 0.0f) {
      EXPECT_EQ(out.stats.error.passes, kMaxErrorPasses);
    }
    return image_error(out.mosaic, reference.mosaic, &reflected).relative_rmse;
  };
  // A target out of reach: every pass.
  return {error(0.0f, false), error(1e-5f, false), error(1e-5f, true)};
}

// With kernels fixed each pass keeps its bias, and their mean with it; progressive passes
// take part of it away: the cells' blur of a sharp shadow, the uniformly lit lobe at a
// chain's end.
TEST(ProbeErrorTarget, ProgressivePassesShrinkTheBias) {
  PHYIR_SKIP_UNDER_SANITIZERS("ProbeErrorTarget.LaterPassesShrinkTheReuseKernels");
  const PassErrors shadow = pass_errors(shadow_room(), glm::vec3(0.25f, 0.3f, 0.05f), 1.0f);
  const PassErrors mirror = pass_errors(mirror_room(), glm::vec3(1.0f, 1.0f, 0.3f), 5.0f);
  RecordProperty("shadow", fmt::format("one pass {:.4f}, 16 fixed {:.4f}, 16 progressive {:.4f}", shadow.once,
                                       shadow.fixed, shadow.progressive));
  RecordProperty("mirror", fmt::format("one pass {:.4f}, 16 fixed {:.4f}, 16 progressive {:.4f}", mirror.once,
                                       mirror.fixed, mirror.progressive));
  EXPECT_LT(shadow.progressive, 0.8 * shadow.fixed) << shadow.fixed << " -> " << shadow.progressive;
  EXPECT_LT(mirror.progressive, 0.8 * mirror.fixed) << mirror.fixed << " -> " << mirror.progressive;
}

TEST(ProbeErrorTarget, RejectsANegativeTarget) {
  ProbeSettings s;
  s.target_error = -0.1f;
  EXPECT_THROW(s.validate(), SettingError);
}

}  // namespace
}  // namespace phyir::render
