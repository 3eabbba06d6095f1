// Consistency of probes with the image (issue 4, item 3): integrating a pixel's probe
// against that pixel's BRDF, as the network's rendering layer does (sum over the texels of
// the upper hemisphere of f_r L cos times the texel's solid angle, f_r at the texel centre,
// with the G-buffer's normal, base colour, roughness and metalness), gives the pixel's
// colour in color.exr. A diffuse and a glossy metal pixel on a flat floor under a ceiling
// light, both modes. Small perspective views (a 1 cm pixel footprint) so the box-filtered
// pixel and the probe 1 cm above its centre see the same thing.
#include <gtest/gtest.h>

#include "phyir/core/safe_math.h"
#include "phyir/render/brdf.h"
#include "phyir/render/equirect.h"
#include "phyir/render/frame.h"
#include "phyir/render/probe_renderer.h"
#include "phyir/render/render_view.h"
#include "test_scenes.h"
#include "sanitizer_skip.h"

namespace phyir::render {
namespace {

// Room [-2, 2] x [0, 3] x [-2, 2]: diffuse walls and ceiling, a 0.8 m ceiling light, the floor's
// x < 0 half diffuse and its x > 0 half a glossy metal.
scenes::Scene consistency_room() {
  scenes::Scene scene;
  const glm::vec3 lo(-2.0f, 0.0f, -2.0f), hi(2.0f, 3.0f, 2.0f);
  const glm::vec3 ex(4, 0, 0), ey(0, 3, 0), ez(0, 0, 4);
  const int wall = test::add_material(scene, test::make_material(glm::vec3(0.7f, 0.6f, 0.5f), 0.8f));
  const int diffuse = test::add_material(scene, test::make_material(glm::vec3(0.5f, 0.55f, 0.6f), 0.9f));
  const int metal = test::add_material(scene, test::make_material(glm::vec3(0.9f, 0.7f, 0.5f), 0.35f, 1.0f));
  const int light = test::add_material(scene, test::make_emitter(glm::vec3(8.0f)));
  test::add_quad(scene, lo, ey, ez, wall, "-X");
  test::add_quad(scene, lo + ex, ez, ey, wall, "+X");
  test::add_quad(scene, lo + ey, ex, ez, wall, "ceiling");
  test::add_quad(scene, lo, ex, ey, wall, "-Z");
  test::add_quad(scene, lo + ez, ey, ex, wall, "+Z");
  test::add_quad(scene, lo, glm::vec3(0, 0, 4), glm::vec3(2, 0, 0), diffuse, "floor x<0");
  test::add_quad(scene, glm::vec3(0, 0, -2), glm::vec3(0, 0, 4), glm::vec3(2, 0, 0), metal, "floor x>0");
  test::add_quad(scene, glm::vec3(-0.4f, 2.99f, -0.4f), glm::vec3(0.8f, 0, 0), glm::vec3(0, 0, 0.8f), light, "light");
  (void)hi;
  return scene;
}

struct Case {
  const char* name;
  glm::vec3 target;  // floor point the centre pixel looks at
  glm::vec3 eye;
  int probe_h, probe_w;
  double tolerance;  // relative, per channel
};

// The rendering layer's integral of one probe for one pixel.
glm::dvec3 integrate(const Image& probe, const glm::vec3& normal, const glm::vec3& wo_world, const BrdfParams& p) {
  const Frame frame(normal);
  const glm::vec3 wo = frame.to_local(wo_world);
  glm::dvec3 sum(0.0);
  for (int r = 0; r < probe.height; ++r) {
    const double solid_angle = equirect_texel_solid_angle(r, probe.width, probe.height);
    for (int c = 0; c < probe.width; ++c) {
      const glm::vec3 d = equirect_direction(glm::vec2((c + 0.5f) / probe.width, (r + 0.5f) / probe.height));
      const glm::vec3 wi = frame.to_local(d);
      if (!(wi.z > 0.0f)) continue;
      const glm::vec3 L(probe.at(c, r, 0), probe.at(c, r, 1), probe.at(c, r, 2));
      sum += glm::dvec3(brdf_eval(p, wo, wi) * L) * double(wi.z) * solid_angle;
    }
  }
  return sum;
}

TEST(ProbeConsistency, IntegratingAPixelsProbeAgainstItsBrdfGivesItsColour) {
  PHYIR_SKIP_UNDER_SANITIZERS("ProbeRobustness.* and StabilityMatrix.ProbesEveryMaterialAndMode");
  const scenes::Scene scene = consistency_room();
  const RenderScene rs(scene);
  const Effects effects = analyse_effects(scene, false);
  // The glossy case looks at the metal from the mirror direction of the light's centre, so
  // the light's highlight is inside the lobe: the hardest part of the integral.
  const glm::vec3 glossy_target(0.9f, 0.0f, 0.5f);
  const glm::vec3 to_light = glm::normalize(glm::vec3(0.0f, 2.99f, 0.0f) - glossy_target);
  const glm::vec3 mirror_eye = glossy_target + 1.6f * glm::vec3(-to_light.x, to_light.y, -to_light.z);
  const Case cases[] = {
      {"diffuse", glm::vec3(-0.8f, 0.0f, 0.3f), glm::vec3(-1.4f, 1.5f, 1.3f), 16, 32, 0.04},
      {"glossy metal, R = 0.35", glossy_target, mirror_eye, 64, 128, 0.06},
  };
  for (const Case& k : cases) {
    CameraModel camera;
    camera.projection = Projection::Perspective;
    camera.position = k.eye;
    camera.forward = glm::normalize(k.target - k.eye);
    camera.up = glm::vec3(0, 1, 0);
    camera.yfov = 0.015f;  // 3 pixels of 5 mrad: under 1 cm on the floor
    camera.width = camera.height = 3;
    RenderSettings view;
    view.spp = 8192;
    view.seed = 1;
    view.progress = false;
    const RenderOutput image = render_view(rs, camera, view);
    const int px = 1, py = 1;
    ASSERT_EQ(image.film.aov("mask_geometry").at(px, py), 1.0f);
    const glm::vec3 normal(image.film.aov("normal").at(px, py, 0), image.film.aov("normal").at(px, py, 1),
                           image.film.aov("normal").at(px, py, 2));
    const BrdfParams p{glm::vec3(image.film.aov("basecolor").at(px, py, 0), image.film.aov("basecolor").at(px, py, 1),
                                 image.film.aov("basecolor").at(px, py, 2)),
                       image.film.aov("roughness").at(px, py), image.film.aov("metalness").at(px, py)};
    const glm::vec3 wo = -camera.generate_ray(glm::vec2(px + 0.5f, py + 0.5f)).direction;

    for (ProbeMode mode : {ProbeMode::kCache, ProbeMode::kPath}) {
      ProbeSettings s;
      s.layout = ProbeLayout{3, 3, k.probe_h, k.probe_w};  // grid = image: probe (i, j) at pixel (j, i)'s centre
      s.mode = mode;
      s.spp = mode == ProbeMode::kPath ? (k.probe_h == 16 ? 256 : 16) : 16;
      s.cache.samples_per_cell = 256;
      s.seed = 3;
      s.progress = false;
      const std::vector<ProbeSite> sites = place_probes(rs, camera, s.layout, s.offset);
      const int index = py * 3 + px;
      ASSERT_TRUE(sites[size_t(index)].valid());
      EXPECT_NEAR(glm::length(sites[size_t(index)].normal - normal), 0.0f, 1e-6f);
      const ProbeOutput out = ProbeRenderer(rs, effects, s).render_at(sites, {index});
      const Image probe = probe_image(out.mosaic, s.layout, py, px);
      const glm::dvec3 rendered = integrate(probe, normal, wo, p);
      for (int ch = 0; ch < 3; ++ch) {
        const double colour = image.film.color().at(px, py, ch);
        std::printf("[ %s, %s ] channel %d: color.exr %.5f, probe integral %.5f (%+.2f%%)\n", k.name,
                    probe_mode_name(mode).c_str(), ch, colour, rendered[ch], 100.0 * (rendered[ch] / colour - 1.0));
        EXPECT_NEAR(rendered[ch], colour, k.tolerance * colour) << k.name << ", " << probe_mode_name(mode);
      }
    }
  }
}

}  // namespace
}  // namespace phyir::render
