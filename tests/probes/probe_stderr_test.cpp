// The per-texel standard error (ProbeOutput::standard_error, probe_stderr.exr) of path mode,
// the unbiased estimator: calibrated against a reference of many more directions, at 16, 64
// and 256 directions per texel. Per texel
// of a few probes in a lit box room with a glossy floor and a box, e = luminance(estimate -
// reference) and sigma = sqrt(stderr^2 + stderr_ref^2), measured by probe_calibration (its own
// test: probe_calibration_test.cpp). Checked: the median ratio (|e| / sigma / 0.6745) within
// [0.8, 1.25] and at least 90% within 2 sigma, the calibration criterion. Cache mode
// with a deliberately noisy cache meets it too: its sigma carries the cache's fill noise.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "phyir/render/probe_calibration.h"
#include "phyir/render/probe_renderer.h"
#include "sanitizer_skip.h"
#include "single_probe.h"
#include "test_scenes.h"

namespace phyir::render {
namespace {

scenes::Scene lit_room() {
  scenes::Scene scene = test::make_box_room(glm::vec3(-2.0f, 0.0f, -2.0f), glm::vec3(2.0f, 3.0f, 2.0f),
                                            test::make_material(glm::vec3(0.7f, 0.6f, 0.5f), 0.8f));
  const int glossy = test::add_material(scene, test::make_material(glm::vec3(0.9f, 0.8f, 0.6f), 0.3f, 1.0f));
  const int light = test::add_material(scene, test::make_emitter(glm::vec3(6.0f)));
  test::add_quad(scene, glm::vec3(-1.5f, 0.001f, -1.5f), glm::vec3(0, 0, 3), glm::vec3(3, 0, 0), glossy, "glossy floor");
  test::add_box(scene, glm::vec3(0.6f, 0.0f, -0.4f), glm::vec3(1.2f, 0.8f, 0.4f), 0);
  test::add_quad(scene, glm::vec3(-0.5f, 2.99f, -0.5f), glm::vec3(1, 0, 0), glm::vec3(0, 0, 1), light, "light");
  return scene;
}

// A dim room lit by a small bright bulb (5 cm sphere) 30 cm from a probe: hard light.
scenes::Scene bulb_room() {
  scenes::Scene scene = test::make_box_room(glm::vec3(-2.0f, 0.0f, -2.0f), glm::vec3(2.0f, 3.0f, 2.0f),
                                            test::make_material(glm::vec3(0.6f), 0.9f));
  const int bulb = test::add_material(scene, test::make_emitter(glm::vec3(400.0f)));
  test::add_uv_sphere(scene, glm::vec3(-0.3f, 1.5f, -1.0f), 0.05f, bulb, 16, 8);
  return scene;
}

std::vector<ProbeSite> sites() {
  std::vector<ProbeSite> out;
  for (const glm::vec3& p : {glm::vec3(-1.0f, 0.3f, 0.5f), glm::vec3(0.2f, 1.2f, -1.0f), glm::vec3(-0.3f, 0.05f, -1.2f),
                             glm::vec3(1.5f, 2.0f, 1.5f)})
    out.push_back(single_site(p).front());
  return out;
}

ProbeOutput render_path(const RenderScene& rs, const Effects& effects, int spp, uint64_t seed, int max_bounces = 4) {
  ProbeSettings s;
  s.mode = ProbeMode::kPath;
  s.spp = spp;
  s.layout = {1, 4, 8, 16};
  s.path.max_bounces = max_bounces;
  s.seed = seed;
  s.progress = false;
  return ProbeRenderer(rs, effects, s).render_at(sites());
}


// Images stacked top to bottom (the same width and channels).
Image stacked(const std::vector<Image>& images) {
  Image out(images.front().width, 0, images.front().channels);
  for (const Image& image : images) {
    out.pixels.insert(out.pixels.end(), image.pixels.begin(), image.pixels.end());
    out.height += image.height;
  }
  return out;
}

// The calibration of `scene`'s probes at `spp` (three seeds pooled) against a reference of
// 4096 directions, measured by probe_calibration.
void expect_calibrated(const scenes::Scene& scene, const char* name) {
  const RenderScene rs(scene);
  const Effects effects = analyse_effects(scene, false);
  const ProbeOutput reference = render_path(rs, effects, 4096, 101);
  for (int spp : {16, 64, 256}) {
    std::vector<Image> values, errors, references, reference_errors;
    for (uint64_t seed : {1, 2, 3}) {
      const ProbeOutput out = render_path(rs, effects, spp, seed);
      ASSERT_EQ(out.standard_error.width, out.mosaic.width);
      for (float s : out.standard_error.pixels) ASSERT_TRUE(std::isfinite(s) && s >= 0.0f);
      values.push_back(out.mosaic);
      errors.push_back(out.standard_error);
      references.push_back(reference.mosaic);
      reference_errors.push_back(reference.standard_error);
    }
    const ProbeCalibration c =
        probe_calibration(stacked(values), stacked(errors), stacked(references), stacked(reference_errors));
    ASSERT_GT(c.texels, 1000u);
    EXPECT_GE(c.median_ratio, 0.8) << name << ", " << spp << " spp";
    EXPECT_LE(c.median_ratio, 1.25) << name << ", " << spp << " spp";
    EXPECT_GE(c.within_two_sigma, 0.9) << name << ", " << spp << " spp";
    std::printf("%s, path mode, %d spp: median |e|/sigma / 0.6745 = %.3f, within 2 sigma %.3f (%zu texels)\n", name,
                spp, c.median_ratio, c.within_two_sigma, c.texels);
  }
}

// Cache mode at `spp` with a cache of `cache_spp` estimates a cell, the default 8 bounces: its
// calibration over three seeds against the path-mode reference (no foot correction or sharing
// at four lone probes).
ProbeCalibration cache_mode_calibration(const scenes::Scene& scene, int spp, int cache_spp) {
  constexpr int kBounces = 8;
  const RenderScene rs(scene);
  const Effects effects = analyse_effects(scene, false);
  const ProbeOutput reference = render_path(rs, effects, 4096, 101, kBounces);
  std::vector<Image> values, errors, references, reference_errors;
  for (uint64_t seed : {1, 2, 3}) {
    ProbeSettings s;
    s.mode = ProbeMode::kCache;
    s.spp = spp;
    s.cache.samples_per_cell = cache_spp;
    s.layout = {1, 4, 8, 16};
    s.path.max_bounces = kBounces;
    s.seed = seed;
    s.progress = false;
    const ProbeOutput out = ProbeRenderer(rs, effects, s).render_at(sites());
    values.push_back(out.mosaic);
    errors.push_back(out.standard_error);
    references.push_back(reference.mosaic);
    reference_errors.push_back(reference.standard_error);
  }
  return probe_calibration(stacked(values), stacked(errors), stacked(references), stacked(reference_errors));
}

}  // namespace

TEST(ProbeStandardError, CacheModeCountsTheCachesFillNoise) {
  PHYIR_SKIP_UNDER_SANITIZERS("ProbeRenderer.* (the same renderer at fewer directions)");
  // 64 directions a texel, 8 estimates a cache cell, 8 bounces: much of a diffuse texel's error
  // is the cells' fill noise, which its own directions share and cannot show. Without it in
  // sigma the bulb room fails (median ratio 1.11, 85% within 2 sigma; with it 0.90, 96%); the
  // lit room's gold floor, whose specular chains end in the cache with the path's throughput,
  // is dominated by its own noise (1.07, 95% without; 1.06, 95% with).
  for (const auto& [name, scene] : {std::pair("lit room", lit_room()), std::pair("bulb room", bulb_room())}) {
    const ProbeCalibration c = cache_mode_calibration(scene, 64, 8);
    std::printf("%s, cache mode, 64 spp, 8 estimates a cell: median |e|/sigma / 0.6745 = %.3f, within 2 sigma %.3f\n",
                name, c.median_ratio, c.within_two_sigma);
    ASSERT_GT(c.texels, 1000u);
    EXPECT_GE(c.median_ratio, 0.8) << name;
    EXPECT_LE(c.median_ratio, 1.25) << name;
    EXPECT_GE(c.within_two_sigma, 0.9) << name;
  }
}

TEST(ProbeStandardError, PathModeIsCalibratedInALitRoomWithAGlossyFloor) {
  PHYIR_SKIP_UNDER_SANITIZERS("ProbeRenderer.* (the same renderer at fewer directions)");
  expect_calibrated(lit_room(), "lit room");
}

TEST(ProbeStandardError, PathModeIsCalibratedNearABulb) {
  PHYIR_SKIP_UNDER_SANITIZERS("ProbeRenderer.* (the same renderer at fewer directions)");
  expect_calibrated(bulb_room(), "bulb room");
}

}  // namespace phyir::render
