// Probe texels against exact answers: an enclosure of emitting walls (emission only: every
// texel exactly the wall's radiance; one bounce: 1 + the Fresnel reflection the model adds,
// computed here by quadrature), the layout read back by (i, j) in a room of six differently
// coloured emitting walls (origin and orientation), the mirror symmetry of a probe at the
// centre of a symmetric room, determinism across thread counts, and no NaN or negative
// texel in a room with metal, a mirror and glass. Both modes throughout.
#include <gtest/gtest.h>

#include <tbb/global_control.h>

#include <array>
#include <cmath>
#include <vector>
#include <limits>

#include "phyir/core/image_error.h"
#include "phyir/core/safe_math.h"
#include "phyir/render/brdf.h"
#include "phyir/render/effects.h"
#include "phyir/render/equirect.h"
#include "phyir/render/probe_renderer.h"
#include "single_probe.h"
#include "test_scenes.h"
#include "sanitizer_skip.h"

namespace phyir::render {
namespace {

// The box [-1, 1]^3 seen from inside, every wall emitting 1 with base colour 0 (roughness 1).
scenes::Scene enclosure() {
  scenes::Scene scene;
  const int m = test::add_material(scene, test::make_emitter(glm::vec3(1.0f)));
  test::add_box(scene, glm::vec3(-1.0f), glm::vec3(1.0f), m, /*inward=*/true, "enclosure");
  return scene;
}

const ProbeMode kModes[] = {ProbeMode::kPath, ProbeMode::kCache};

TEST(ProbeEnclosure, EmissionOnlyEveryTexelIsExactlyTheWallRadiance) {
  const scenes::Scene scene = enclosure();
  for (ProbeMode mode : kModes) {
    const Image probe = render_single(scene, glm::vec3(0.2f, -0.1f, 0.3f), settings_for(mode, 4, 8, 16, 0));
    for (float v : probe.pixels) ASSERT_EQ(v, 1.0f) << probe_mode_name(mode);
  }
}

// Directional albedo of the enclosure's material (B = 0, R = 1, M = 0: F0 = 0.04, the
// specular lobe alone) at n.v, by midpoint quadrature over the hemisphere.
double enclosure_albedo(double NoV) {
  const BrdfParams p{glm::vec3(0.0f), 1.0f, 0.0f};
  const glm::vec3 wo(float(std::sqrt(std::max(0.0, 1.0 - NoV * NoV))), 0.0f, float(NoV));
  const int nt = 256, np = 256;
  double sum = 0.0;
  for (int i = 0; i < nt; ++i) {
    const double theta = (i + 0.5) * (kPi / 2) / nt;
    for (int j = 0; j < np; ++j) {
      const double phi = (j + 0.5) * kPi / np;  // symmetric in phi: half the circle, doubled
      const glm::vec3 wi(float(std::sin(theta) * std::cos(phi)), float(std::sin(theta) * std::sin(phi)), float(std::cos(theta)));
      sum += double(brdf_eval(p, wo, wi).x) * wi.z * std::sin(theta);
    }
  }
  return 2.0 * sum * (kPi / 2 / nt) * (kPi / np);
}

// Emission only, a ceiling light partly hidden by a bar under it: cache mode's light
// texels (the exact unoccluded coverage plus sampled directions for the rest, the control
// variate of EmitterCoverage) against path mode at many directions: per texel within the
// noise, and the light's total.
TEST(ProbeLights, APartlyHiddenLightMatchesThePathMode) {
  scenes::Scene scene;
  // cross(edge_u, edge_v) = -Y: emits downwards.
  test::add_quad(scene, glm::vec3(-0.3f, 2.6f, -0.3f), glm::vec3(0.6f, 0, 0), glm::vec3(0, 0, 0.6f),
                 test::add_material(scene, test::make_emitter(glm::vec3(20.0f))), "light");
  test::add_box(scene, glm::vec3(-0.5f, 2.3f, -0.04f), glm::vec3(0.5f, 2.35f, 0.06f),
                test::add_material(scene, test::make_material(glm::vec3(0.5f), 1.0f, 0.0f)), "bar");
  const glm::vec3 origin(0.05f, 0.0f, 0.17f);
  const Image path = render_single(scene, origin, settings_for(ProbeMode::kPath, 16384, 16, 32, 0));
  const Image cache = render_single(scene, origin, settings_for(ProbeMode::kCache, 4, 16, 32, 0));
  double total_path = 0.0, total_cache = 0.0, worst = 0.0;
  int lit = 0;
  for (int r = 0; r < 16; ++r)
    for (int c = 0; c < 32; ++c) {
      const double a = path.at(c, r, 0), b = cache.at(c, r, 0), omega = equirect_texel_solid_angle(r, 32, 16);
      total_path += a * omega;
      total_cache += b * omega;
      if (a > 0.0 || b > 0.0) ++lit;
      worst = std::max(worst, std::abs(a - b) / 20.0);
    }
  std::printf("[ partly hidden light ] %d lit texels, irradiance-like total path %.5f cache %.5f (%+.3f%%), worst texel %.4f of the light\n",
              lit, total_path, total_cache, 100.0 * (total_cache / total_path - 1.0), worst);
  EXPECT_GT(lit, 4);
  EXPECT_NEAR(total_cache / total_path, 1.0, 0.01);
  // Path mode's 16384 directions leave ~0.4% of the light per texel at a shadow edge, cache
  // mode's 64-1024 (the occluded part only) a few percent.
  EXPECT_LT(worst, 0.05);
}

// The enclosure's walls seen from `origin`: per texel of an h x w probe, the exact one-bounce
// value, the mean of 1 + A(n.v) over the texel (8 x 8 directions, each's wall found
// analytically: the slab it leaves the box through), and the mean of ceil(8 A(n.v)).
struct EnclosureView {
  std::vector<double> exact, ceil_8a;
};

EnclosureView enclosure_view(const glm::vec3& origin, int h, int w) {
  constexpr int kTable = 65;
  std::vector<double> albedo(kTable);
  for (int k = 0; k < kTable; ++k) albedo[k] = enclosure_albedo(std::max(double(k) / (kTable - 1), 1e-4));
  auto A = [&](double NoV) {
    const double x = std::clamp(NoV, 0.0, 1.0) * (kTable - 1);
    const int k = std::min(int(x), kTable - 2);
    return albedo[k] + (x - k) * (albedo[k + 1] - albedo[k]);
  };
  EnclosureView v;
  for (int r = 0; r < h; ++r)
    for (int c = 0; c < w; ++c) {
      double exact = 0.0, ceil_8a = 0.0;
      for (int a = 0; a < 8; ++a)
        for (int b = 0; b < 8; ++b) {
          const glm::vec3 d = probe_texel_direction(r, c, h, w, glm::vec2((a + 0.5f) / 8, (b + 0.5f) / 8));
          float t = std::numeric_limits<float>::infinity();
          int axis = 0;
          for (int k = 0; k < 3; ++k) {
            if (d[k] == 0.0f) continue;
            const float tk = ((d[k] > 0 ? 1.0f : -1.0f) - origin[k]) / d[k];
            if (tk < t) t = tk, axis = k;
          }
          exact += 1.0 + A(std::abs(d[axis]));
          ceil_8a += std::ceil(8.0 * A(std::abs(d[axis])));
        }
      v.exact.push_back(exact / 64.0);
      v.ceil_8a.push_back(ceil_8a / 64.0);
    }
  return v;
}

TEST(ProbeEnclosure, OneBounceEveryTexelIsOnePlusTheFresnelReflectionOfTheWalls) {
  // L_i(d) = Le + integral of f_s Le cos = 1 + A(n.v at the wall hit along d). Base colour 0
  // leaves only the model's specular lobe, which still reflects 1-2% (more at grazing).
  const scenes::Scene scene = enclosure();
  const glm::vec3 origin(0.2f, -0.1f, 0.3f);
  const int h = 8, w = 16;
  const EnclosureView view = enclosure_view(origin, h, w);
  for (ProbeMode mode : kModes) {
    // Cache mode samples a black emitter's reflection with one light sample per direction
    // (its albedo's share of 8): at 64 directions the largest difference is ~4e-3.
    const Image probe = render_single(scene, origin, settings_for(mode, mode == ProbeMode::kPath ? 128 : 64, h, w, 1));
    double worst = 0.0;
    for (int r = 0; r < h; ++r)
      for (int c = 0; c < w; ++c) {
        const double expected = view.exact[size_t(r * w + c)];
        for (int ch = 0; ch < 3; ++ch) {
          const double v = probe.at(c, r, ch);
          worst = std::max(worst, std::abs(v - expected));
          // The reflection is 1-3% of the texel; its Monte Carlo noise here is ~1-2e-3.
          ASSERT_NEAR(v, expected, 6e-3) << probe_mode_name(mode) << " texel " << r << "," << c;
          ASSERT_GT(v, 1.005) << "the Fresnel reflection is missing";
        }
      }
    std::printf("[ enclosure, one bounce, %s ] largest |texel - exact| = %.5f\n", probe_mode_name(mode).c_str(), worst);
  }
}

// Every texel sees an emitter whose emission is exact and whose reflection is a few percent
// of it: the default cache mode (4 directions) must neither supersample the texels (their
// rest spreads by at most the walls' albedo, far under 0.75 x the emission; no light's
// outline crosses a texel, the box's creases being seen from inside) nor spend 8 light
// samples at each hit. Each direction of the rest costs its ray, the BRDF-sampled ray and
// one shadow ray per light sample, ceil(8 A(n.v)) of them (A = the walls' albedo, at least
// one): at most 2 + the mean of ceil(8 A) over the texels (~3), where each took 10 (1 + 8 +
// 1) in 6 x as many directions before. The texels still equal the exact answer.
TEST(ProbeEnclosure, NearlyBlackEmittingWallsAreNeitherSupersampledNorLightSampledMoreThanTheirAlbedoAsks) {
  const scenes::Scene scene = enclosure();
  const glm::vec3 origin(0.2f, -0.1f, 0.3f);
  const int h = 8, w = 16, spp = 4;
  const EnclosureView view = enclosure_view(origin, h, w);
  const RenderScene rs(scene);
  const ProbeOutput out = ProbeRenderer(rs, analyse_effects(scene, false), settings_for(ProbeMode::kCache, spp, h, w, 1))
                              .render_at(single_site(origin));
  const ProbeStats& st = out.stats;
  const double texels = double(h * w);
  double bound = 0.0, worst = 0.0, mean_error = 0.0;
  for (int t = 0; t < h * w; ++t) {
    bound += (2.0 + view.ceil_8a[size_t(t)]) / texels;
    for (int ch = 0; ch < 3; ++ch) {
      const double e = out.mosaic.at(t % w, t / w, ch) - view.exact[size_t(t)];
      worst = std::max(worst, std::abs(e));
      mean_error += e / (3.0 * texels);
    }
  }
  const double rest_rays = double(st.counters.rays - st.cache_rays - st.emission_rays) / (texels * spp);
  // A lone probe leaves cells undiscovered: each such lookup traces one more ray (one bounce).
  bound += double(st.cache_fallbacks) / (texels * spp);
  std::printf("[ enclosure, default spp ] %llu of %d texels supersampled, %llu outline texels, %.3f rays per direction "
              "of the rest (bound %.3f), |texel - exact| mean %.5f largest %.5f\n",
              static_cast<unsigned long long>(st.supersampled_texels), h * w,
              static_cast<unsigned long long>(st.light_edge_texels), rest_rays, bound, mean_error, worst);
  EXPECT_EQ(st.light_texels, uint64_t(h * w));
  EXPECT_EQ(st.light_edge_texels, 0u);
  EXPECT_EQ(st.supersampled_texels, 0u);
  EXPECT_LE(rest_rays, bound);
  // 4 directions of one light sample each leave up to ~2% of noise in a texel (its
  // reflection's); over the probe they average to the exact value.
  EXPECT_LT(worst, 0.04);
  EXPECT_NEAR(mean_error, 0.0, 2e-3);
}

// A room [-2, 2] x [0, 3] x [-1.5, 1.5] whose six walls emit six different colours.
const glm::vec3 kRoomMin(-2.0f, 0.0f, -1.5f), kRoomMax(2.0f, 3.0f, 1.5f);
const glm::vec3 kWallColour[6] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 0}, {0, 1, 1}, {1, 0, 1}};  // -X,+X,-Y,+Y,-Z,+Z

scenes::Scene coloured_room() {
  scenes::Scene scene;
  const glm::vec3 d = kRoomMax - kRoomMin;
  const glm::vec3 ex(d.x, 0, 0), ey(0, d.y, 0), ez(0, 0, d.z);
  int m[6];
  for (int k = 0; k < 6; ++k) m[k] = test::add_material(scene, test::make_emitter(kWallColour[k]));
  test::add_quad(scene, kRoomMin, ey, ez, m[0], "-X");
  test::add_quad(scene, kRoomMin + ex, ez, ey, m[1], "+X");
  test::add_quad(scene, kRoomMin, ez, ex, m[2], "floor");
  test::add_quad(scene, kRoomMin + ey, ex, ez, m[3], "ceiling");
  test::add_quad(scene, kRoomMin, ex, ey, m[4], "-Z");
  test::add_quad(scene, kRoomMin + ez, ey, ex, m[5], "+Z");
  return scene;
}

// The wall (index into kWallColour) a ray from inside the room leaves through, and where.
int exit_wall(const glm::vec3& o, const glm::vec3& d, float* t_out = nullptr) {
  float t = std::numeric_limits<float>::infinity();
  int wall = -1;
  for (int k = 0; k < 3; ++k) {
    if (d[k] == 0.0f) continue;
    const float tk = ((d[k] > 0 ? kRoomMax[k] : kRoomMin[k]) - o[k]) / d[k];
    if (tk < t) t = tk, wall = 2 * k + (d[k] > 0 ? 1 : 0);
  }
  if (t_out) *t_out = t;
  return wall;
}

TEST(ProbeLayout, ReadingProbeIJBackGivesItsOriginAndAWorldAlignedImage) {
  const scenes::Scene scene = coloured_room();
  const RenderScene rs(scene);
  CameraModel camera;
  camera.position = glm::vec3(0.3f, 1.2f, -0.2f);
  camera.width = 32;
  camera.height = 16;
  for (ProbeMode mode : kModes) {
    ProbeSettings s = settings_for(mode, 4, 8, 16, 0);
    s.layout.grid_height = 4;
    s.layout.grid_width = 8;
    const ProbeOutput out = render_probes(rs, camera, analyse_effects(scene, false), s);
    ASSERT_EQ(out.mosaic.width, 8 * 16);
    ASSERT_EQ(out.mosaic.height, 4 * 8);
    int uniform_texels = 0;
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 8; ++j) {
        // Origin: the camera ray through grid cell (i, j)'s centre, to the wall, 1 cm back
        // along the wall's inward normal.
        const glm::vec3 d = equirect_direction(glm::vec2((j + 0.5f) / 8, (i + 0.5f) / 4));
        float t;
        const int wall = exit_wall(camera.position, d, &t);
        glm::vec3 normal(0.0f);
        normal[wall / 2] = (wall % 2) ? -1.0f : 1.0f;
        const glm::vec3 origin = camera.position + t * d + 0.01f * normal;
        for (int c = 0; c < 3; ++c) {
          EXPECT_NEAR(out.position.at(j, i, c), origin[c], 1e-4f) << i << "," << j;
          EXPECT_EQ(out.normal.at(j, i, c), normal[c]) << i << "," << j;
        }
        EXPECT_EQ(out.mask.at(j, i), 0.0f) << "every wall emits, so no probe is a valid label";
        // Orientation: every texel whose whole solid angle sees one wall is that wall's colour.
        const Image probe = probe_image(out.mosaic, s.layout, i, j);
        for (int r = 0; r < 8; ++r)
          for (int c = 0; c < 16; ++c) {
            int seen = -2;
            for (int a = 0; a < 5 && seen != -1; ++a)
              for (int b = 0; b < 5 && seen != -1; ++b) {
                const int k = exit_wall(origin, probe_texel_direction(r, c, 8, 16, glm::vec2(a / 4.0f, b / 4.0f)));
                seen = (seen == -2 || seen == k) ? k : -1;
              }
            if (seen < 0) continue;
            ++uniform_texels;
            for (int ch = 0; ch < 3; ++ch)
              ASSERT_EQ(probe.at(c, r, ch), kWallColour[seen][ch]) << probe_mode_name(mode) << " probe " << i << "," << j
                                                                   << " texel " << r << "," << c << " sees wall " << seen;
          }
      }
    EXPECT_GT(uniform_texels, 4 * 8 * 8 * 16 / 2);
  }
}

scenes::Scene symmetric_room() {
  scenes::Scene scene = test::make_box_room(glm::vec3(-2.0f, 0.0f, -2.0f), glm::vec3(2.0f, 3.0f, 2.0f),
                                            test::make_material(glm::vec3(0.6f), 0.8f));
  const int light = test::add_material(scene, test::make_emitter(glm::vec3(8.0f)));
  test::add_quad(scene, glm::vec3(-0.4f, 2.99f, -0.4f), glm::vec3(0.8f, 0, 0), glm::vec3(0, 0, 0.8f), light, "light");
  return scene;
}

// RMS of the difference between a probe and its mirror image in x (column c <-> w - 1 - c).
double mirror_rms(const Image& p) {
  double sum = 0.0;
  for (int r = 0; r < p.height; ++r)
    for (int c = 0; c < p.width; ++c)
      for (int ch = 0; ch < 3; ++ch) {
        const double d = p.at(c, r, ch) - p.at(p.width - 1 - c, r, ch);
        sum += d * d;
      }
  return std::sqrt(sum / (p.width * p.height * 3.0));
}

double rms_difference(const Image& a, const Image& b) {
  double sum = 0.0;
  for (size_t k = 0; k < a.pixels.size(); ++k) sum += double(a.pixels[k] - b.pixels[k]) * (a.pixels[k] - b.pixels[k]);
  return std::sqrt(sum / a.pixels.size());
}

TEST(ProbeSymmetry, AProbeAtTheCentreOfASymmetricRoomIsItsOwnMirrorImage) {
  const scenes::Scene scene = symmetric_room();
  const glm::vec3 centre(0.0f, 1.5f, 0.0f);
  for (ProbeMode mode : kModes) {
    ProbeSettings s = settings_for(mode, mode == ProbeMode::kPath ? 64 : 16, 16, 32);
    const Image a = render_single(scene, centre, s);
    s.seed = 6;
    const Image b = render_single(scene, centre, s);
    // A probe and its mirror image differ by noise only: as much as two independent
    // renders of it do (both are differences of two independent estimates).
    const double noise = rms_difference(a, b), mirror = mirror_rms(a);
    std::printf("[ symmetric room, %s ] RMS(probe - mirror) = %.5f, RMS(seed 5 - seed 6) = %.5f\n",
                probe_mode_name(mode).c_str(), mirror, noise);
    EXPECT_LT(mirror, 1.5 * noise + 1e-4) << probe_mode_name(mode);
    // And it is not symmetric under a quarter turn about a wrong axis (the test can fail):
    // rows mirrored top to bottom (floor <-> ceiling) differ by far more than noise.
    double flipped = 0.0;
    for (int r = 0; r < 16; ++r)
      for (int c = 0; c < 32; ++c) flipped += std::pow(a.at(c, r, 1) - a.at(c, 15 - r, 1), 2.0);
    EXPECT_GT(std::sqrt(flipped / 512), 5 * noise);
  }
}

scenes::Scene lit_room_with_everything() {
  scenes::Scene scene = test::make_box_room(glm::vec3(-2.0f, 0.0f, -1.5f), glm::vec3(2.0f, 3.0f, 1.5f));
  const int light = test::add_material(scene, test::make_emitter(glm::vec3(10.0f)));
  test::add_quad(scene, glm::vec3(-0.3f, 2.95f, -0.3f), glm::vec3(0.6f, 0, 0), glm::vec3(0, 0, 0.6f), light, "light");
  const int metal = test::add_material(scene, test::make_material(glm::vec3(0.9f, 0.6f, 0.3f), 0.2f, 1.0f));
  test::add_uv_sphere(scene, glm::vec3(0.8f, 0.5f, 0.4f), 0.4f, metal, 24, 12);
  const int mirror = test::add_material(scene, test::make_material(glm::vec3(0.95f), 0.0f, 1.0f));
  test::add_quad(scene, glm::vec3(1.99f, 0.5f, 1.0f), glm::vec3(0, 0, -1.0f), glm::vec3(0, 1.5f, 0), mirror, "mirror");
  scenes::Material glass = test::make_material(glm::vec3(1.0f), 0.0f);
  glass.transmission_factor = 1.0f;
  const int g = test::add_material(scene, glass);
  test::add_uv_sphere(scene, glm::vec3(-0.8f, 0.4f, -0.3f), 0.3f, g, 24, 12);
  return scene;
}

ProbeSettings grid_settings(ProbeMode mode) {
  ProbeSettings s = settings_for(mode, 4, 8, 16);
  s.layout.grid_height = 4;
  s.layout.grid_width = 8;
  s.cache.samples_per_cell = 16;
  return s;
}

TEST(ProbeDeterminism, SameSeedSameProbesWhateverTheThreadCount) {
  const scenes::Scene scene = lit_room_with_everything();
  const RenderScene rs(scene);
  const Effects effects = analyse_effects(scene, false);
  CameraModel camera;
  camera.position = glm::vec3(0.0f, 1.5f, 0.0f);
  for (ProbeMode mode : kModes) {
    Image one, two;
    {
      tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
      one = render_probes(rs, camera, effects, grid_settings(mode)).mosaic;
    }
    {
      tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
      two = render_probes(rs, camera, effects, grid_settings(mode)).mosaic;
    }
    EXPECT_EQ(one.pixels, two.pixels) << probe_mode_name(mode);
    ProbeSettings other = grid_settings(mode);
    other.seed = 6;
    EXPECT_NE(render_probes(rs, camera, effects, other).mosaic.pixels, one.pixels) << probe_mode_name(mode);
  }
}

TEST(ProbeRobustness, NoTexelIsNegativeOrNonFiniteWithMetalMirrorAndGlass) {
  const scenes::Scene scene = lit_room_with_everything();
  const RenderScene rs(scene);
  const Effects effects = analyse_effects(scene, false);
  ASSERT_TRUE(effects.transmission && effects.mirrors);
  CameraModel camera;
  camera.position = glm::vec3(0.0f, 1.5f, 0.0f);
  for (ProbeMode mode : kModes) {
    ProbeSettings s = grid_settings(mode);
    s.layout.grid_height = 8;  // fine enough to put probes on the glass sphere
    s.layout.grid_width = 16;
    s.spp = 2;
    const ProbeOutput out = render_probes(rs, camera, effects, s);
    EXPECT_EQ(out.stats.counters.nonfinite_samples, 0u);
    EXPECT_GT(out.stats.transparent, 0u);
    EXPECT_GT(out.stats.valid, 0u);
    for (float v : out.mosaic.pixels) ASSERT_TRUE(std::isfinite(v) && v >= 0.0f) << probe_mode_name(mode);
    double sum = 0.0;
    for (float v : out.mosaic.pixels) sum += v;
    EXPECT_GT(sum, 0.0);
  }
}

// The cache mode's two regimes against the unbiased path mode, in a room of glossy
// dielectric walls (roughness 0.5: the specular lobe is a sizeable share) with a small
// hanging light: a probe between the light and a pillar's top 20 cm under it sees that top
// within the cache's near-light distance (direct light sampled per direction, several
// light samples per estimate, multi-sample MIS), a probe near the floor far from it sees cells
// whose direct light is cached (the specular lobe estimated apart, its GGX ray
// Russian-rouletted, MIS with the rouletted density). Each probe's mean and its
// cosine-weighted upper-hemisphere sum agree within noise plus the cache's few-percent
// interpolation bias.
// With a bulb (a point light) beside the panel too, the texels near both take the panel by
// light samples that never choose the bulb, and the bulb exactly (punctual_light), the
// panel's hits weighted against those samples alone: any mismatch of the two is a bias here.
TEST(ProbeCache, NearAndFarFromALightMatchesThePathMode) {
  PHYIR_SKIP_UNDER_SANITIZERS("ProbeLights.APartlyHiddenLightMatchesThePathMode, ProbeRobustness.*, StabilityMatrix.ProbesEveryMaterialAndMode");
  for (const bool bulb : {false, true}) {
  scenes::Scene scene =
      test::make_box_room(glm::vec3(-2.0f, 0.0f, -1.5f), glm::vec3(2.0f, 3.0f, 1.5f), test::make_material(glm::vec3(0.7f), 0.5f, 0.0f));
  const int light = test::add_material(scene, test::make_emitter(glm::vec3(20.0f)));
  test::add_quad(scene, glm::vec3(-0.2f, 2.6f, -0.2f), glm::vec3(0.4f, 0, 0), glm::vec3(0, 0, 0.4f), light, "light");
  // A pillar whose top is 20 cm under the light: cells there hold no direct light.
  test::add_box(scene, glm::vec3(-0.4f, 0.0f, -0.4f), glm::vec3(0.4f, 2.4f, 0.4f),
                test::add_material(scene, test::make_material(glm::vec3(0.6f), 0.4f, 0.0f)));
  if (bulb) scene.lights = {test::make_point_light(1.5f, glm::vec3(0.35f, 2.5f, 0.1f))};
  const struct {
    const char* name;
    glm::vec3 origin;
  } probes[] = {{"between the light and the pillar", glm::vec3(0.1f, 2.45f, 0.05f)},
                {"far from the light", glm::vec3(-1.5f, 0.3f, 1.0f)}};
  for (const auto& probe : probes) {
    if (bulb && probe.origin.y < 1.0f) continue;  // the bulb's texels are near it
    // Far from the light the path mode's mean varies by 3% between seeds at 512 directions
    // (paths that find the light after several bounces); 4096 keep it well inside the 3%.
    ProbeSettings path = settings_for(ProbeMode::kPath, 4096, 16, 32, 4);
    ProbeSettings cache = settings_for(ProbeMode::kCache, 64, 16, 32, 4);
    cache.cache.samples_per_cell = 1024;
    const Image a = render_single(scene, probe.origin, path), b = render_single(scene, probe.origin, cache);
    double mean_a = 0.0, mean_b = 0.0, up_a = 0.0, up_b = 0.0;
    for (int r = 0; r < 16; ++r)
      for (int c = 0; c < 32; ++c) {
        const glm::vec3 d = equirect_direction(glm::vec2((c + 0.5f) / 32.0f, (r + 0.5f) / 16.0f));
        const double w = equirect_texel_solid_angle(r, 32, 16) * std::max(d.y, 0.0f);
        for (int ch = 0; ch < 3; ++ch) {
          mean_a += a.at(c, r, ch), mean_b += b.at(c, r, ch);
          up_a += w * a.at(c, r, ch), up_b += w * b.at(c, r, ch);
        }
      }
    std::printf("[ %s%s ] mean path %.4f cache %.4f (%+.2f%%), upward irradiance path %.4f cache %.4f (%+.2f%%)\n",
                probe.name, bulb ? ", with a bulb" : "", mean_a / 1536, mean_b / 1536, 100 * (mean_b / mean_a - 1),
                up_a / 3, up_b / 3, 100 * (up_b / up_a - 1));
    EXPECT_NEAR(mean_b / mean_a, 1.0, 0.03) << probe.name << " bulb " << bulb;
    EXPECT_NEAR(up_b / up_a, 1.0, 0.03) << probe.name << " bulb " << bulb;
  }
  }
}

// A room lit only by punctual lights (a point light and a spot): the cache mode's texels
// match the path mode's near the point light and far from it. The lights' own texels are
// left out (they are exact in both modes, punctual_deposit_test.cpp), so that the estimated
// light is compared alone, and no texel of the estimate sees a light itself (no ray can hit
// one: the texel looking at the lamp shows the wall behind it, not a spike).
TEST(ProbeLights, PunctualLightsLightTheTexelsAsInThePathMode) {
  PHYIR_SKIP_UNDER_SANITIZERS("PunctualDeposit.* and StabilityMatrix.ProbesEveryMaterialAndMode");
  const glm::vec3 lo(-2.0f, 0.0f, -1.5f), hi(2.0f, 3.0f, 1.5f);
  scenes::Scene scene = test::make_box_room(lo, hi, test::make_material(glm::vec3(0.7f), 0.5f, 0.0f));
  using Type = scenes::PunctualLight::Type;
  scene.lights = {test::make_punctual_light(Type::Point, 3.0f, glm::vec3(0.5f, 2.2f, 0.0f), glm::vec3(0, -1, 0)),
                  test::make_punctual_light(Type::Spot, 8.0f, glm::vec3(-1.5f, 2.8f, 1.0f), glm::vec3(0.3f, -1, -0.3f))};
  const Effects effects = analyse_effects(scene, false);
  ASSERT_TRUE(effects.punctual_lights && !effects.emitters);
  const struct {
    const char* name;
    glm::vec3 origin;
  } probes[] = {{"30 cm under the point light", glm::vec3(0.5f, 1.9f, 0.0f)}, {"far from both", glm::vec3(1.6f, 0.3f, -1.2f)}};
  for (const auto& probe : probes) {
    ProbeSettings path = settings_for(ProbeMode::kPath, 512, 16, 32, 4);
    ProbeSettings cache = settings_for(ProbeMode::kCache, 64, 16, 32, 4);
    cache.cache.samples_per_cell = 1024;
    path.punctual_lights = cache.punctual_lights = false;
    const Image a = render_single(scene, probe.origin, path), b = render_single(scene, probe.origin, cache);
    double mean_a = 0.0, mean_b = 0.0, max_a = 0.0;
    for (int r = 0; r < 16; ++r)
      for (int c = 0; c < 32; ++c)
        for (int ch = 0; ch < 3; ++ch) {
          mean_a += a.at(c, r, ch), mean_b += b.at(c, r, ch);
          max_a = std::max(max_a, double(a.at(c, r, ch)));
        }
    mean_a /= 1536, mean_b /= 1536;
    std::printf("[ %s ] mean path %.4f cache %.4f (%+.2f%%), brightest path texel %.2f x the mean\n", probe.name,
                mean_a, mean_b, 100 * (mean_b / mean_a - 1), max_a / mean_a);
    EXPECT_GT(mean_a, 0.0) << probe.name;
    EXPECT_NEAR(mean_b / mean_a, 1.0, 0.03) << probe.name;
    EXPECT_LT(max_a, 10.0 * mean_a) << probe.name;  // the lit ceiling above the lamp, not the lamp
  }
}

// A dim 4 x 2.5 x 4 m room whose ceiling a narrow spot 1.5 m under it lights in a small disc.
scenes::Scene spot_disc_room(float inner_cone, float outer_cone) {
  scenes::Scene scene = test::make_box_room({-2.0f, 0.0f, -2.0f}, {2.0f, 2.5f, 2.0f},
                                            test::make_material(glm::vec3(0.3f)));
  scenes::PunctualLight spot;
  spot.type = scenes::PunctualLight::Type::Spot;
  spot.intensity = 50.0f * scenes::PunctualLight::kLumensPerWatt;
  spot.position = glm::vec3(0.8f, 1.0f, 0.4f);
  spot.direction = glm::vec3(0.0f, 1.0f, 0.0f);
  spot.inner_cone_angle = inner_cone;
  spot.outer_cone_angle = outer_cone;
  scene.lights = {spot};
  return scene;
}

// A narrow spot's small, bright disc on the ceiling of a dim room: the texels that hold a
// small part of it spread over their hard samples by far more than their mean, and are
// estimated again from 4 x as many fresh directions (stats.deep_texels); the probe still
// agrees with path mode texel by texel where the disc is.
TEST(ProbeDeepTexels, ARareBrightPartIsSampledDeeperAndTheProbeStillMatchesThePathMode) {
  const scenes::Scene scene = spot_disc_room(0.05f, 0.06f);  // a disc of about 9 cm on the ceiling
  const glm::vec3 origin(0.0f, 1.0f, 0.0f);
  const int h = 16, w = 32;
  ProbeSettings cache = settings_for(ProbeMode::kCache, 4, h, w, 2);
  ProbeSettings path = settings_for(ProbeMode::kPath, 4096, h, w, 2);
  cache.punctual_lights = path.punctual_lights = false;
  const RenderScene rs(scene);
  const ProbeOutput out = ProbeRenderer(rs, analyse_effects(scene, false), cache).render_at(single_site(origin));
  const Image reference = render_single(scene, origin, path);
  // The disc's texels: the reference's brightest, against the probe's mean.
  double mean = 0.0, disc_ref = 0.0, disc_cache = 0.0;
  for (int r = 0; r < h; ++r)
    for (int c = 0; c < w; ++c) mean += reference.at(c, r, 0) / double(h * w);
  for (int r = 0; r < h; ++r)
    for (int c = 0; c < w; ++c)
      if (reference.at(c, r, 0) > 10.0 * mean) disc_ref += reference.at(c, r, 0), disc_cache += out.mosaic.at(c, r, 0);
  std::printf("[ spot disc ] %llu deep texels of %llu supersampled; the disc's texels: cache %.3f path %.3f\n",
              static_cast<unsigned long long>(out.stats.deep_texels),
              static_cast<unsigned long long>(out.stats.supersampled_texels), disc_cache, disc_ref);
  EXPECT_GT(out.stats.deep_texels, 0u);
  EXPECT_LT(out.stats.deep_texels, out.stats.supersampled_texels);
  ASSERT_GT(disc_ref, 0.0);
  EXPECT_NEAR(disc_cache / disc_ref, 1.0, 0.1);
}

// A spot's disc on the ceiling of a dim room (outer cone `cone`) seen from the room's middle:
// the texels that hold it (the path mode's, above twice the probe's mean) and their value.
struct DiscTexels {
  float cone = 0.0f;
  std::vector<glm::ivec2> texels;
  double path = 0.0;
};

constexpr int kDiscH = 16, kDiscW = 32;
const glm::vec3 kDiscOrigin(0.0f, 1.0f, 0.0f);

DiscTexels disc_texels(float cone) {
  ProbeSettings path = settings_for(ProbeMode::kPath, 4096, kDiscH, kDiscW, 2);
  path.punctual_lights = false;
  const Image reference = render_single(spot_disc_room(0.8f * cone, cone), kDiscOrigin, path);
  double mean = 0.0;
  for (int r = 0; r < kDiscH; ++r)
    for (int c = 0; c < kDiscW; ++c) mean += reference.at(c, r, 0) / double(kDiscH * kDiscW);
  DiscTexels disc;
  disc.cone = cone;
  for (int r = 0; r < kDiscH; ++r)
    for (int c = 0; c < kDiscW; ++c)
      if (reference.at(c, r, 0) > 2.0 * mean) disc.texels.push_back({c, r}), disc.path += reference.at(c, r, 0);
  EXPECT_GE(disc.texels.size(), 1u);
  return disc;
}

// The cache mode's mean of the disc's texels over `seeds` seeds and its standard error.
struct SeedMean {
  double cache = 0.0, standard_error = 0.0, path = 0.0;
};

SeedMean disc_over_seeds(const DiscTexels& disc, int spp, int photons, int seeds, float target_error = 0.0f) {
  const scenes::Scene scene = spot_disc_room(0.8f * disc.cone, disc.cone);
  const RenderScene rs(scene);
  double sum = 0.0, sum2 = 0.0;
  for (int seed = 0; seed < seeds; ++seed) {
    ProbeSettings cache = settings_for(ProbeMode::kCache, spp, kDiscH, kDiscW, 2);
    cache.punctual_lights = false;
    cache.photons_per_light = photons;
    cache.target_error = target_error;
    cache.seed = uint64_t(100 + seed);
    const ProbeOutput probe = ProbeRenderer(rs, analyse_effects(scene, false), cache).render_at(single_site(kDiscOrigin));
    double total = 0.0;
    for (const glm::ivec2& t : disc.texels) total += probe.mosaic.at(t.x, t.y, 0);
    sum += total, sum2 += total * total;
  }
  SeedMean out;
  out.path = disc.path;
  out.cache = sum / seeds;
  out.standard_error = std::sqrt(std::max(0.0, sum2 / seeds - out.cache * out.cache) / (seeds - 1));
  std::printf("[ spot disc, cone %.3f, %d spp, %d photons, target %g ] cache over %d seeds %.5f +- %.5f, path %.5f "
              "(ratio %.3f)\n",
              disc.cone, spp, photons, target_error, seeds, out.cache, out.standard_error, out.path,
              out.cache / out.path);
  return out;
}

// The 9 cm disc, which many of a texel's hard samples miss: averaged over seeds the probe's
// value there is the path mode's (the spot's photons take most of it, the directions the rest).
TEST(ProbeDeepTexels, ARareBrightPartIsUnbiasedOverSeeds) {
  const SeedMean m = disc_over_seeds(disc_texels(0.06f), 4, 4096, 24);
  EXPECT_NEAR(m.cache, m.path, 3.0 * m.standard_error + 0.03 * m.path);
}

// Without photons, a 3 cm disc that a texel's first directions seldom find: a texel whose
// first directions found nothing is not supersampled and keeps them, one that found the disc
// is estimated again from fresh ones, so the disc's light is lost where the first look missed
// it (docs/probes-estimator.md, "Hard texels"). The loss shrinks as the directions grow.
TEST(ProbeDeepTexels, WhatTheFirstLookMissesShrinksAsItsDirectionsGrow) {
  const DiscTexels disc = disc_texels(0.02f);
  const SeedMean few = disc_over_seeds(disc, 4, 0, 24), more = disc_over_seeds(disc, 32, 0, 24);
  EXPECT_GT(more.cache / more.path, few.cache / few.path + 0.3);
  EXPECT_NEAR(more.cache, more.path, 3.0 * more.standard_error + 0.15 * more.path);
}

// The same 3 cm disc under an error target out of reach (16 passes): a later pass also
// supersamples what an earlier pass found, and the passes weigh by their directions, so the
// mean of the passes leaves the first look's loss behind (each pass choosing by its own first
// look alone, equally weighted, kept it: 0.16, where one pass has it).
TEST(ProbeDeepTexels, PassesToAnErrorTargetLeaveTheFirstLooksLossBehind) {
  const SeedMean m = disc_over_seeds(disc_texels(0.02f), 4, 0, 12, 1e-6f);
  EXPECT_NEAR(m.cache, m.path, 3.0 * m.standard_error + 0.1 * m.path);
}

// Cache mode at 4 spp on the disc's probe, the spot's own light and photons left out.
ProbeSettings disc_cache_settings(float balance, uint64_t seed) {
  ProbeSettings cache = settings_for(ProbeMode::kCache, 4, kDiscH, kDiscW, 2);
  cache.punctual_lights = false;
  cache.photons_per_light = 0;
  cache.balance = balance;
  cache.seed = seed;
  return cache;
}

// Without photons a spot's 60 cm disc on the ceiling holds nearly all of the probe's noise:
// balancing gives its texels the probe's extra directions (docs/probes-estimator.md,
// "Balancing the texels' noise"), which cuts the probe's error against path mode (measured
// 0.32 -> 0.11 for 11% more rays; bounded by twice).
TEST(ProbeBalance, TheExtraDirectionsGoWhereTheNoiseIsAndCutTheProbesError) {
  const scenes::Scene scene = spot_disc_room(0.16f, 0.2f);  // a disc of about 60 cm on the ceiling
  ProbeSettings path = settings_for(ProbeMode::kPath, 4096, kDiscH, kDiscW, 2);
  path.punctual_lights = false;
  const Image reference = render_single(scene, kDiscOrigin, path);
  const RenderScene rs(scene);
  auto error_and_rays = [&](float balance) {
    double error = 0.0, rays = 0.0, balanced = 0.0;
    const int seeds = 4;
    for (int seed = 0; seed < seeds; ++seed) {
      const ProbeSettings cache = disc_cache_settings(balance, uint64_t(200 + seed));
      const ProbeOutput out = ProbeRenderer(rs, analyse_effects(scene, false), cache).render_at(single_site(kDiscOrigin));
      error += image_error(out.mosaic, reference).relative_rmse / seeds;
      rays += double(out.stats.counters.rays) / seeds;
      balanced += double(out.stats.balanced_texels) / seeds;
    }
    std::printf("[ balance %.1f ] relative RMSE %.4f, %.0f rays, %.1f texels balanced\n", balance, error, rays, balanced);
    return std::array<double, 3>{error, rays, balanced};
  };
  const auto none = error_and_rays(0.0f), once = error_and_rays(1.0f);
  EXPECT_EQ(none[2], 0.0);
  EXPECT_GT(once[2], 0.0);
  EXPECT_LT(once[0], 0.6 * none[0]);
  EXPECT_LT(once[1], 2.2 * none[1]);
}

// The same disc's probe in one tile with a probe inside a dark, closed box beside the room,
// whose texels have no noise: the tile's extra directions (balance x all its directions)
// follow the noise across its probes, so the disc's texels take the dark probe's share too
// (about twice the extra directions they take alone; shared out per probe, measured 1.3x,
// the cache differing with the probes that found its cells), and they still cut its error.
TEST(ProbeBalance, ATilesExtraDirectionsGoToItsNoisiestProbe) {
  scenes::Scene scene = spot_disc_room(0.16f, 0.2f);
  test::add_box(scene, {5.0f, 0.0f, -0.5f}, {6.0f, 1.0f, 0.5f}, test::add_material(scene, test::make_material()), true);
  ProbeSettings path = settings_for(ProbeMode::kPath, 4096, kDiscH, kDiscW, 2);
  path.punctual_lights = false;
  const Image reference = render_single(scene, kDiscOrigin, path);
  const RenderScene rs(scene);
  std::vector<ProbeSite> pair = single_site(kDiscOrigin);
  pair.push_back(single_site(glm::vec3(5.5f, 0.5f, 0.0f)).front());
  struct Run { double rays = 0.0, error = 0.0; };
  auto run = [&](float balance, bool with_dark_probe) {
    Run r;
    const int seeds = 4;
    for (int seed = 0; seed < seeds; ++seed) {
      ProbeSettings cache = disc_cache_settings(balance, uint64_t(300 + seed));
      if (with_dark_probe) cache.layout.grid_width = 2;
      const ProbeOutput out = ProbeRenderer(rs, analyse_effects(scene, false), cache)
                                  .render_at(with_dark_probe ? pair : single_site(kDiscOrigin));
      r.rays += double(out.stats.counters.rays) / seeds;
      const Image disc_probe = probe_image(out.mosaic, out.layout, 0, 0);
      r.error += image_error(disc_probe, reference).relative_rmse / seeds;
    }
    return r;
  };
  const Run alone0 = run(0.0f, false), alone1 = run(1.0f, false), pair0 = run(0.0f, true), pair1 = run(1.0f, true);
  const double extra_alone = alone1.rays - alone0.rays, extra_pair = pair1.rays - pair0.rays;
  std::printf("[ tile balance ] extra rays: %.0f alone, %.0f beside the dark probe; the disc probe's error alone %.4f -> %.4f, "
              "beside it %.4f -> %.4f\n", extra_alone, extra_pair, alone0.error, alone1.error, pair0.error, pair1.error);
  ASSERT_GT(extra_alone, 0.0);
  EXPECT_GT(extra_pair, 1.5 * extra_alone);
  EXPECT_LT(pair1.error, 0.6 * pair0.error);
}

}  // namespace
}  // namespace phyir::render
