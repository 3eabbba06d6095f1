// The stability matrix's probe rows (docs/robustness.md; the rest: tests/render/
// stability_matrix_test.cpp): probes on every hard material, in both modes, at extreme scales
// and inside objects give finite, non-negative texels.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "phyir/core/safe_math.h"
#include "phyir/render/effects.h"
#include "phyir/render/probe_renderer.h"
#include "stability_helpers.h"
#include "test_scenes.h"

namespace phyir::render {
namespace {

using namespace stability;

// Small, fast probes: 2 x 4 probes of 4 x 8 texels (or `layout`), a 16-estimate cache.
ProbeSettings small_probes(ProbeMode mode, int spp, const ProbeLayout& layout = ProbeLayout{2, 4, 4, 8}) {
  ProbeSettings s;
  s.mode = mode;
  s.spp = spp;
  s.layout = layout;
  s.cache.samples_per_cell = 16;
  s.progress = false;
  return s;
}

// Every texel finite and non-negative, no non-finite sample caught.
void expect_finite(const ProbeOutput& out, const std::string& what) {
  EXPECT_EQ(out.stats.counters.nonfinite_samples, 0u) << what;
  for (float v : out.mosaic.pixels) ASSERT_TRUE(std::isfinite(v) && v >= 0.0f) << what;
}

// --- Probes ----------------------------------------------------------------------------------

TEST(StabilityMatrix, ProbesEveryMaterialAndMode) {
  // Probes sit on the test material (the floor and the sphere), so their rays leave from it
  // and see mirrors and metals of every roughness; 2 x 4 probes of 4 x 8 texels.
  uint64_t cases = 0;
  for (const BrdfParams& p : material_matrix()) {
    scenes::Scene scene = lit_room(p);
    const int hot = test::add_material(scene, test::make_emitter(glm::vec3(1e6f), true, "hot"));
    test::add_quad(scene, glm::vec3(0.0f, 2.0f, 0.0f), glm::vec3(0.01f, 0, 0), glm::vec3(0, 0, 0.01f), hot);
    const RenderScene rs(scene);
    for (ProbeMode mode : {ProbeMode::kPath, ProbeMode::kCache}) {
      ProbeSettings s = small_probes(mode, 2);
      s.cache.cell_size = 0.5f;
      s.hard_spp_factor = 2;
      s.seed = 4;
      const std::vector<ProbeSite> sites = place_probes(rs, panorama(glm::vec3(-0.4f, 1.4f, 0.6f)), s.layout, s.offset);
      const ProbeOutput out = ProbeRenderer(rs, analyse_effects(scene, false), s).render_at(sites);
      ++cases;
      expect_finite(out, describe(p) + " " + probe_mode_name(mode));
    }
  }
  report("probes (36 materials x 2 modes, radiance 1e6 emitter)", cases);
}

TEST(StabilityMatrix, ProbesAtExtremeScalesAndInsideObjects) {
  uint64_t cases = 0;
  const BrdfParams metal{glm::vec3(1.0f), 1e-3f, 1.0f};
  for (float scale : {1e-3f, 1e3f}) {
    scenes::Scene scene = scaled(lit_room(metal), scale);
    const RenderScene rs(scene);
    for (ProbeMode mode : {ProbeMode::kPath, ProbeMode::kCache}) {
      ProbeSettings s = small_probes(mode, 2);
      s.cache.cell_size = std::clamp(0.5f * scale, 1e-3f, 10.0f);
      s.offset = std::clamp(0.01f * scale, 1e-4f, 1.0f);
      const std::vector<ProbeSite> sites = place_probes(rs, panorama(scale * glm::vec3(-0.4f, 1.4f, 0.6f)), s.layout, s.offset);
      const ProbeOutput out = ProbeRenderer(rs, analyse_effects(scene, false), s).render_at(sites);
      ++cases;
      expect_finite(out, "scale " + std::to_string(scale));
    }
  }
  {  // A probe site inside a closed box (origin in the dark, all walls seen from behind).
    scenes::Scene scene = lit_room(metal);
    test::add_box(scene, glm::vec3(-1.2f, 0.5f, -1.2f), glm::vec3(-0.6f, 1.1f, -0.6f), 0);
    const RenderScene rs(scene);
    ProbeSite site;
    site.surface = glm::vec3(-0.9f, 0.5f, -0.9f);
    site.normal = glm::vec3(0, 1, 0);
    site.origin = glm::vec3(-0.9f, 0.8f, -0.9f);
    site.offset = 0.3f;
    site.status = ProbeStatus::kValid;
    for (ProbeMode mode : {ProbeMode::kPath, ProbeMode::kCache}) {
      const ProbeSettings s = small_probes(mode, 4, ProbeLayout{1, 1, 4, 8});
      const ProbeOutput out = ProbeRenderer(rs, analyse_effects(scene, false), s).render_at({site});
      ++cases;
      expect_finite(out, "inside a box");
    }
  }
  report("probes at 1e-3/1e3 m and inside an object", cases);
}

}  // namespace
}  // namespace phyir::render
