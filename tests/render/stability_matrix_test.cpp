// The stability matrix (issue 8; docs/robustness.md): every hard parameter combination of
// the BRDF (eval, pdf, sample) and the path tracer gives (the probes: tests/probes/
// probe_stability_test.cpp) finite, non-negative
// numbers, and no single sample is large because something divided by a near-zero pdf.
//
//  material axes: roughness {0, 1e-6, 1e-3, 0.05, 0.5, 1} x metalness {0, 0.5, 1} x base
//                 colour {0, 1} = 36 materials;
//  angle axes:    n.v and n.l from 1 down to 0 and slightly negative (shading normals),
//                 three relative azimuths, and the degenerate half vectors wo = wi, wo = -wi;
//  scene axes:    an emitter of radiance 1e6, rooms at 1e-3 and 1e3 metre scale, zero-area
//                 and sliver triangles, coincident surfaces, a camera inside an object,
//                 shading normals far from the geometric ones.
// The bounds, and why each holds, are next to the tests. Case counts are printed at the end
// of each test ("[stability] ...") and listed in docs/robustness.md.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "phyir/core/safe_math.h"
#include "phyir/render/brdf.h"
#include "phyir/render/effects.h"
#include "phyir/render/path_tracer.h"
#include "phyir/render/streams.h"
#include "phyir/render/render_view.h"
#include "phyir/render/rng.h"
#include "stability_helpers.h"
#include "test_scenes.h"

namespace phyir::render {
namespace {

using namespace stability;

// n.v and n.l: from head-on to grazing, through kMinCosine (1e-4), to slightly below the
// surface, as a shading normal tilted away from the geometric one produces.
constexpr float kCosines[] = {1.0f, 0.7f, 0.3f, 0.1f, 1e-2f, 1e-3f, 2e-4f, 1e-4f, 5e-5f, 0.0f, -1e-4f, -1e-2f};
// Azimuth of wi relative to wo: the same side (wo = wi when the cosines agree), across, and
// opposite (the mirror plane, where the specular peak lies).
constexpr float kAzimuths[] = {0.0f, 0.5f * kPi, kPi};



// A unit direction with the given cosine to n = +z and azimuth phi (cos may be negative).
glm::vec3 direction(float cos_theta, float phi) {
  const float s = safe_sqrt(1.0f - cos_theta * cos_theta);
  return glm::vec3(s * std::cos(phi), s * std::sin(phi), cos_theta);
}

bool finite_non_negative(const glm::vec3& v) { return is_finite(v) && v.x >= 0.0f && v.y >= 0.0f && v.z >= 0.0f; }


// --- BRDF ------------------------------------------------------------------------------------

TEST(StabilityMatrix, BrdfEvalAndPdfAreFiniteForEveryMaterialAndAngle) {
  uint64_t cases = 0;
  for (const BrdfParams& p : material_matrix()) {
    for (float cv : kCosines)
      for (float cl : kCosines)
        for (float phi : kAzimuths) {
          const glm::vec3 wo = direction(cv, 0.0f), wi = direction(cl, phi);
          const glm::vec3 f = brdf_eval(p, wo, wi);
          const float pdf = brdf_pdf(p, wo, wi);
          ++cases;
          ASSERT_TRUE(finite_non_negative(f)) << describe(p) << " n.v=" << cv << " n.l=" << cl << " phi=" << phi;
          ASSERT_TRUE(std::isfinite(pdf) && pdf >= 0.0f) << describe(p) << " n.v=" << cv << " n.l=" << cl;
          // Below kMinCosine nothing is reflected (no 1/cos firefly from a grazing pair).
          if (cv < kMinCosine || cl < kMinCosine) {
            EXPECT_EQ(max_component(f), 0.0f) << describe(p) << " n.v=" << cv << " n.l=" << cl;
            EXPECT_EQ(pdf, 0.0f);
          }
          // Reciprocity holds bit for bit, even at the extremes.
          EXPECT_EQ(f, brdf_eval(p, wi, wo)) << describe(p) << " n.v=" << cv << " n.l=" << cl;
        }
  }
  report("BRDF eval+pdf (36 materials x 12 n.v x 12 n.l x 3 azimuths)", cases);
}

TEST(StabilityMatrix, DegenerateHalfVectorsGiveFiniteValues) {
  // wo = wi: h = wo, VoH = 1 (the retro-reflection peak). wo = -wi: wo + wi = 0 and the half
  // vector does not exist; one of the two is always below the surface, so f = 0. Also the
  // exact tangent plane and the normal itself.
  uint64_t cases = 0;
  for (const BrdfParams& p : material_matrix()) {
    for (float c : kCosines)
      for (float phi : kAzimuths) {
        const glm::vec3 w = direction(c, phi);
        for (const auto& [wo, wi] : {std::make_pair(w, w), std::make_pair(w, -w), std::make_pair(-w, w)}) {
          const glm::vec3 f = brdf_eval(p, wo, wi);
          const float pdf = brdf_pdf(p, wo, wi);
          ++cases;
          ASSERT_TRUE(finite_non_negative(f)) << describe(p) << " cos=" << c << " phi=" << phi;
          ASSERT_TRUE(std::isfinite(pdf) && pdf >= 0.0f) << describe(p) << " cos=" << c;
          if (wo == -wi) {
            EXPECT_EQ(max_component(f), 0.0f) << describe(p) << " cos=" << c;
          }
        }
      }
    // Exactly in the tangent plane, and wo = wi = n.
    for (const auto& [wo, wi] : {std::make_pair(glm::vec3(1, 0, 0), glm::vec3(1, 0, 0)),
                                 std::make_pair(glm::vec3(1, 0, 0), glm::vec3(-1, 0, 0)),
                                 std::make_pair(glm::vec3(0, 0, 1), glm::vec3(0, 0, 1)),
                                 std::make_pair(glm::vec3(0, 0, 1), glm::vec3(0, 0, -1))}) {
      ++cases;
      ASSERT_TRUE(finite_non_negative(brdf_eval(p, wo, wi))) << describe(p);
      ASSERT_TRUE(std::isfinite(brdf_pdf(p, wo, wi))) << describe(p);
    }
  }
  report("BRDF degenerate half vectors", cases);
}

// The most a sample's weight f cos / pdf can be, for material p viewed at n.v:
//   f cos / ((1-ps) p_d + ps p_s) <= f_d cos / ((1-ps) p_d) + f_s cos / (ps p_s).
// Diffuse: f_d cos / p_d = B (1-M), so that term is <= max(B (1-M)) / (1-ps).
// Specular: with p_s = D NoH / (4 VoH) the D cancels (so nothing here depends on alpha):
//   f_s cos / p_s = F G VoH / (NoV NoH) = 2 F G VoH^2 / (NoV (NoV + NoL))
// using NoV + NoL = n.(wo+wi) = 2 VoH NoH. With G1(x) = x / (x (1-k) + k) <= min(1, x/k)
// for k <= 1, G <= (NoV/k) (NoL/k) / ... gives f_s cos / p_s <= 2 F / k^2 <= 2 / k^2, and
// k = (R+1)^2/8 >= 1/8. The mirror lobe's weight is F G1^2 / ps <= 1 / ps.
// ps is clamped to [0.05, 0.95] when both lobes exist, so over the whole matrix the weight
// is at most 1/0.05 + 2 * 64 / 0.05 = 2580 (kMaxBrdfSampleWeight); the per-case bound below
// is tighter (e.g. 8 for a rough metal).
constexpr float kMaxBrdfSampleWeight = 2580.0f;

float brdf_weight_bound(const BrdfParams& p, float NoV) {
  const float ps = specular_probability(p, NoV);
  const float diffuse = ps < 1.0f ? max_component(p.base_color * (1.0f - p.metalness)) / (1.0f - ps) : 0.0f;
  const float r1 = clamp01(p.roughness) + 1.0f;
  const float k = r1 * r1 / 8.0f;
  const float specular = is_mirror(p.roughness) ? 1.0f / ps : 2.0f / (k * k * ps);
  return diffuse + specular;
}

TEST(StabilityMatrix, BrdfSampleWeightsAreFiniteAndBounded) {
  uint64_t cases = 0, accepted = 0;
  float worst_fraction = 0.0f, worst_glossy = 0.0f;  // largest weight / its bound seen (all, non-delta)
  for (const BrdfParams& p : material_matrix()) {
    for (float cv : kCosines) {
      const glm::vec3 wo = direction(cv, 0.3f);
      const float bound = brdf_weight_bound(p, std::max(cv, 0.0f));
      ASSERT_LE(bound, kMaxBrdfSampleWeight * 1.0001f) << describe(p);
      // 256 stratified samples per lobe choice, plus the corners of [0,1)^3.
      Rng rng(uint64_t(cases) + 1, 7);
      std::vector<std::pair<float, glm::vec2>> us;
      for (int i = 0; i < 16; ++i)
        for (int j = 0; j < 16; ++j) {
          const glm::vec2 u((i + rng.next_float()) / 16.0f, (j + rng.next_float()) / 16.0f);
          us.push_back({rng.next_float(), u});
        }
      for (float ul : {0.0f, 0.5f, kOneMinusEpsilon})
        for (float a : {0.0f, kOneMinusEpsilon})
          for (float b : {0.0f, kOneMinusEpsilon}) us.push_back({ul, glm::vec2(a, b)});
      for (const auto& [u_lobe, u] : us) {
        BrdfSample s;
        const bool ok = brdf_sample(p, wo, u_lobe, u, &s);
        ++cases;
        if (cv < kMinCosine) {
          ASSERT_FALSE(ok) << describe(p) << " n.v=" << cv;  // below the surface: nothing
          continue;
        }
        if (!ok) {
          EXPECT_EQ(max_component(s.weight), 0.0f);
          continue;
        }
        ++accepted;
        ASSERT_TRUE(finite_non_negative(s.weight)) << describe(p) << " n.v=" << cv;
        ASSERT_TRUE(std::isfinite(s.pdf) && s.pdf > 0.0f) << describe(p) << " n.v=" << cv;
        ASSERT_TRUE(is_finite(s.wi) && std::abs(glm::length(s.wi) - 1.0f) < 1e-4f) << describe(p);
        ASSERT_GE(s.wi.z, 0.0f) << describe(p);
        const float w = max_component(s.weight);
        ASSERT_LE(w, bound) << describe(p) << " n.v=" << cv << " u_lobe=" << u_lobe << " u=(" << u.x << ", "
                            << u.y << ") pdf=" << s.pdf << " delta=" << s.delta;
        worst_fraction = std::max(worst_fraction, w / bound);
        if (!s.delta) worst_glossy = std::max(worst_glossy, w / bound);
      }
    }
  }
  std::printf("[stability] BRDF sample: largest weight reached %.3f of its bound (%.3f for non-delta samples)\n",
              worst_fraction, worst_glossy);
  report("BRDF sample (36 materials x 12 n.v x 268 random-number triples)", cases);
  EXPECT_GT(accepted, cases / 2);
}

// --- Path tracer -----------------------------------------------------------------------------


// Per-sample statistics of a small panorama rendered sample by sample with the path tracer.
struct SampleStats {
  uint64_t samples = 0;
  uint64_t nonfinite = 0;         // caught by the path tracer (counted, returned as 0)
  uint64_t negative = 0;
  float worst_ratio = 0.0f;       // max over pixels of largest sample / max(pixel mean, image mean)
  int worst_x = -1, worst_y = -1;  // where it is
  int worst_nonzero = 0;           // how many of that pixel's samples are not zero
  double image_mean = 0.0;
};

// Russian roulette is off (roulette_start past max_bounces): its 1/q survivor weights are
// legitimate variance, but they would hide what this measures, weights from near-zero pdfs.
PathSettings no_roulette() {
  PathSettings s;
  s.max_bounces = 6;
  s.roulette_start = s.max_bounces + 1;
  return s;
}

SampleStats sample_stats(const scenes::Scene& scene, const CameraModel& camera, int spp,
                         const PathSettings& settings = no_roulette()) {
  const RenderScene rs(scene);
  const PathTracer tracer(rs, analyse_effects(scene, false), settings);
  SampleStats st;
  PathCounters counters;
  struct PixelSamples {
    int x, y, nonzero;
    double mean;
    float largest;
  };
  std::vector<PixelSamples> pixels;
  for (int y = 0; y < camera.height; ++y)
    for (int x = 0; x < camera.width; ++x) {
      const uint64_t pixel = uint64_t(y) * camera.width + x;
      double sum = 0.0;
      float largest = 0.0f;
      int nonzero = 0;
      for (int s = 0; s < spp; ++s) {
        const uint64_t key = sample_key(3, pixel, s);
        Rng jitter(key, 0);
        const glm::vec3 L = tracer.radiance(camera.generate_ray(glm::vec2(x, y) + jitter.next_2d()), key, &counters);
        ++st.samples;
        if (!is_finite(L)) ++st.nonfinite;  // never: radiance() zeroes them, counters count them
        if (L.x < 0.0f || L.y < 0.0f || L.z < 0.0f) ++st.negative;
        const float l = max_component(L);
        sum += l;
        largest = std::max(largest, l);
        nonzero += l > 0.0f;
      }
      const double mean = sum / spp;
      st.image_mean += mean;
      pixels.push_back({x, y, nonzero, mean, largest});
    }
  st.image_mean /= double(camera.width) * camera.height;
  // A pixel's reference value is its mean, but at least the image's mean: a dark pixel (a
  // black metal whose Fresnel edge catches the light in a few samples) legitimately has
  // samples many times its own tiny mean, never many times the image's.
  for (const PixelSamples& p : pixels) {
    const double reference = std::max(p.mean, st.image_mean);
    if (reference > 0.0 && p.largest / reference > st.worst_ratio) {
      st.worst_ratio = float(p.largest / reference);
      st.worst_x = p.x;
      st.worst_y = p.y;
      st.worst_nonzero = p.nonzero;
    }
  }
  st.nonfinite += counters.nonfinite_samples;
  return st;
}

std::string worst_pixel(const SampleStats& st) {
  return "worst pixel (" + std::to_string(st.worst_x) + ", " + std::to_string(st.worst_y) + ") with " +
         std::to_string(st.worst_nonzero) + " non-zero samples";
}

void expect_stable(const SampleStats& st, const std::string& what) {
  EXPECT_EQ(st.nonfinite, 0u) << what;
  EXPECT_EQ(st.negative, 0u) << what;
  EXPECT_TRUE(std::isfinite(st.image_mean)) << what;
}


// The reference value of a pixel is max(its mean, the image mean) (see sample_stats).
// Why a ratio bound: with N samples, largest / mean <= N always (one sample carrying the
// whole pixel). A sample that divided by a near-zero pdf (1e-6 and below: a grazing 1/cos, a
// 1/alpha^2 NDF, a light pdf at a coincident point) is 1e3-1e6 times its neighbours, which
// pushes the ratio to N. In this room every radiance is smooth, per-bounce weights are bounded
// (kMaxBrdfSampleWeight; next-event estimation with the power heuristic contributes at most
// f Le cos / (2 pdf_brdf)), and Russian roulette is off (no_roulette()), so a healthy pixel's
// largest sample is a small multiple of its mean: kMaxSampleRatio = N / 4 = 16 means no
// sample may carry a quarter of its pixel. The measured worst over the matrix is printed
// ("[stability] path tracer: ...") and stated in docs/robustness.md.
constexpr int kPathSpp = 64;
constexpr float kMaxSampleRatio = kPathSpp / 4.0f;

TEST(StabilityMatrix, PathTracerEveryMaterialHasBoundedSamples) {
  uint64_t cases = 0, samples = 0;
  float worst = 0.0f;
  for (const BrdfParams& p : material_matrix()) {
    const SampleStats st = sample_stats(lit_room(p), panorama(glm::vec3(-0.4f, 1.4f, 0.6f)), kPathSpp);
    ++cases;
    samples += st.samples;
    expect_stable(st, describe(p));
    EXPECT_GT(st.image_mean, 0.0) << describe(p);
    EXPECT_LT(st.worst_ratio, kMaxSampleRatio) << describe(p) << " " << worst_pixel(st);
    worst = std::max(worst, st.worst_ratio);
  }
  std::printf("[stability] path tracer: worst largest sample / max(pixel mean, image mean) = %.2f (bound %.0f, spp %d)\n",
              worst, kMaxSampleRatio, kPathSpp);
  report("path tracer materials (36 scenes, 16x8 px x 64 spp each)", cases);
  report("path tracer material samples", samples);
}


TEST(StabilityMatrix, PathTracerSceneScales) {
  // The same room at 1 mm and 1 km for a 1 m room: ray offsets scale with the coordinates
  // (ray_offset.h), so the image must be the same up to noise, not black or speckled.
  const BrdfParams glossy{glm::vec3(1.0f), 0.05f, 1.0f};
  const SampleStats reference = sample_stats(lit_room(glossy), panorama(glm::vec3(-0.4f, 1.4f, 0.6f)), kPathSpp);
  uint64_t cases = 0;
  for (float s : {1e-3f, 1e3f}) {
    const SampleStats st =
        sample_stats(scaled(lit_room(glossy), s), panorama(s * glm::vec3(-0.4f, 1.4f, 0.6f)), kPathSpp);
    ++cases;
    expect_stable(st, "scale " + std::to_string(s));
    EXPECT_LT(st.worst_ratio, kMaxSampleRatio) << "scale " << s << " " << worst_pixel(st);
    // Radiance does not depend on scale (same solid angles): within 5% of the 1 m room.
    EXPECT_NEAR(st.image_mean, reference.image_mean, 0.05 * reference.image_mean) << "scale " << s;
  }
  report("path tracer scales (1e-3, 1e3 m)", cases);
}

TEST(StabilityMatrix, PathTracerHardGeometry) {
  uint64_t cases = 0;
  const BrdfParams rough{glm::vec3(0.8f), 0.5f, 0.0f};
  const CameraModel cam = panorama(glm::vec3(-0.4f, 1.4f, 0.6f));

  {  // A tiny emitter of radiance 1e6 (1 cm^2: the power of a 10 W source) seen directly.
    scenes::Scene scene = lit_room(rough);
    const int hot = test::add_material(scene, test::make_emitter(glm::vec3(1e6f), true, "hot"));
    test::add_quad(scene, glm::vec3(0.0f, 2.0f, 0.0f), glm::vec3(0.01f, 0, 0), glm::vec3(0, 0, 0.01f), hot);
    expect_stable(sample_stats(scene, cam, 32), "radiance 1e6");
    ++cases;
  }
  {  // Zero-area and sliver triangles, with zero normals, lit and in view.
    scenes::Scene scene = lit_room(rough);
    scenes::Mesh bad;
    bad.name = "degenerate";
    bad.material = 0;
    bad.positions = {{0, 1, 0}, {0, 1, 0}, {0, 1, 0},                   // a point
                     {0, 1.2f, 0}, {0.5f, 1.2f, 0}, {1, 1.2f, 0},       // collinear
                     {0, 1.4f, 0}, {1, 1.4f, 0}, {0.5f, 1.4f, 1e-9f},   // 1e-9 m wide sliver
                     {0, 1.6f, 0}, {1e-7f, 1.6f, 0}, {0, 1.6f + 1e-7f, 0}};  // 0.1 micron needle
    bad.normals.assign(bad.positions.size(), glm::vec3(0.0f));
    bad.triangles = {{0, 1, 2}, {3, 4, 5}, {6, 7, 8}, {9, 10, 11}};
    test::add_mesh(scene, bad);
    // An emitter made of a sliver: sampled with its tiny area, it must not blow up.
    const int light = test::add_material(scene, test::make_emitter(glm::vec3(100.0f), true, "sliver light"));
    scenes::Mesh sliver;
    sliver.name = "sliver light";
    sliver.material = light;
    sliver.positions = {{-1, 2, 1}, {1, 2, 1}, {0, 2, 1 + 1e-6f}};
    sliver.triangles = {{0, 1, 2}};
    test::add_mesh(scene, sliver);
    expect_stable(sample_stats(scene, cam, 32), "degenerate triangles");
    cases += 2;
  }
  {  // Coincident surfaces: a mirror and a white diffuse quad in the same plane, and a quad
     // in the floor's plane (z-fighting decides nothing numerically bad may happen).
    scenes::Scene scene = lit_room(rough);
    const int mirror = test::add_material(scene, test::make_material(glm::vec3(1.0f), 0.0f, 1.0f, "mirror"));
    const int white = test::add_material(scene, test::make_material(glm::vec3(1.0f), 1.0f, 0.0f, "white"));
    test::add_quad(scene, glm::vec3(-1.5f, 0.3f, -1.9f), glm::vec3(1, 0, 0), glm::vec3(0, 1, 0), mirror);
    test::add_quad(scene, glm::vec3(-1.5f, 0.3f, -1.9f), glm::vec3(1, 0, 0), glm::vec3(0, 1, 0), white);
    test::add_quad(scene, glm::vec3(-1.9f, 0.3f, -1.5f), glm::vec3(0, 1, 0), glm::vec3(0, 0, 1), white);
    test::add_quad(scene, glm::vec3(-1.9f, 0.3f, -1.5f), glm::vec3(0, 0, 1), glm::vec3(0, 1, 0), mirror);  // back to back
    test::add_quad(scene, glm::vec3(-1, 0, -1), glm::vec3(0, 0, 1), glm::vec3(1, 0, 0), white);  // in the floor
    const SampleStats st = sample_stats(scene, cam, kPathSpp);
    expect_stable(st, "coincident surfaces");
    EXPECT_LT(st.worst_ratio, kMaxSampleRatio) << worst_pixel(st);
    ++cases;
  }
  {  // A camera inside closed objects: a box facing out and a sphere (all their walls seen
     // from behind), and exactly on a wall.
    scenes::Scene scene = lit_room(rough);
    test::add_box(scene, glm::vec3(-1.2f, 0.5f, -1.2f), glm::vec3(-0.6f, 1.1f, -0.6f), 0);
    test::add_uv_sphere(scene, glm::vec3(1.0f, 1.5f, 1.0f), 0.3f, 0, 16, 8);
    for (const glm::vec3& p : {glm::vec3(-0.9f, 0.8f, -0.9f), glm::vec3(1.0f, 1.5f, 1.0f), glm::vec3(-2.0f, 1.0f, 0.0f)}) {
      expect_stable(sample_stats(scene, panorama(p), 16), "camera inside");
      ++cases;
    }
  }
  {  // Shading normals far from the geometric ones: n.v < 0 for the shading normal while the
     // geometric normal faces the camera, and normals tangent to the surface.
    scenes::Scene scene = lit_room(rough);
    const int metal = test::add_material(scene, test::make_material(glm::vec3(1.0f), 0.05f, 1.0f, "metal"));
    const int quad = test::add_quad(scene, glm::vec3(-1.5f, 0.01f, -1.5f), glm::vec3(0, 0, 3), glm::vec3(3, 0, 0), metal);
    scenes::Mesh& m = scene.meshes[quad];
    m.normals = {glm::normalize(glm::vec3(1, 0.01f, 0)), glm::normalize(glm::vec3(-1, 0.01f, 0)),
                 glm::vec3(0, 0, 1), glm::normalize(glm::vec3(0.3f, -1, 0))};
    expect_stable(sample_stats(scene, cam, 32), "bent shading normals");
    ++cases;
  }
  report("path tracer hard geometry", cases);
}

// The full renderer (tiles, AOVs, film) on the hardest case of each kind.
TEST(StabilityMatrix, RenderViewAovsStayFinite) {
  scenes::Scene scene = lit_room({glm::vec3(1.0f), 0.0f, 1.0f});
  const int hot = test::add_material(scene, test::make_emitter(glm::vec3(1e6f), true, "hot"));
  test::add_quad(scene, glm::vec3(0.0f, 2.0f, 0.0f), glm::vec3(0.01f, 0, 0), glm::vec3(0, 0, 0.01f), hot);
  uint64_t cases = 0;
  for (float s : {1e-3f, 1.0f, 1e3f}) {
    const scenes::Scene sc = scaled(scene, s);
    const RenderScene rs(sc);
    RenderSettings settings;
    settings.spp = 8;
    settings.seed = 2;
    settings.progress = false;
    const RenderOutput out = render_view(rs, panorama(s * glm::vec3(-0.4f, 1.4f, 0.6f), 32, 16), settings);
    EXPECT_EQ(out.stats.counters.nonfinite_samples, 0u);
    for (float v : out.film.color().pixels) ASSERT_TRUE(std::isfinite(v) && v >= 0.0f);
    for (const std::string& name : Film::aov_names())
      for (float v : out.film.aov(name).pixels) ASSERT_TRUE(std::isfinite(v)) << name << " scale " << s;
    ++cases;
  }
  report("render_view with AOVs (radiance 1e6 at 3 scales)", cases);
}

}  // namespace
}  // namespace phyir::render
