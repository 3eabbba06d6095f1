// Apartments from Debian's real furniture library (sweethome3d-furniture): furnished rooms,
// no meshes crossing, lamps lit at night, daylight through the windows, same bytes for the
// same seed, light samples and rays seeing the lamps alike. Skipped when the package is not
// installed.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>

#include "phyir/core/image_io.h"
#include "phyir/core/safe_math.h"
#include "phyir/render/camera.h"
#include "phyir/render/direct_lighting.h"
#include "phyir/render/ray_offset.h"
#include "phyir/render/rng.h"
#include "phyir/render/sampling.h"
#include "phyir/render/render_scene.h"
#include "phyir/render/render_view.h"
#include "phyir/scenes/apartment_generator.h"
#include "phyir/scenes/gltf_loader.h"
#include "monte_carlo.h"

namespace phyir {
namespace {

namespace fs = std::filesystem;
using scenes::ApartmentLighting;

bool library_installed() { return fs::exists(scenes::kDefaultAssetDir); }

const scenes::AssetLibrary& real_library() {
  static const scenes::AssetLibrary library = scenes::AssetLibrary::open(scenes::kDefaultAssetDir);
  return library;
}

fs::path temp_dir(const std::string& name) {
  const fs::path dir = fs::path(::testing::TempDir()) / "phyir_apartment_test" / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// Mean radiance of a 32 x 32 perspective view (60 degrees) from `eye` along `forward`, with
// the scene's declared environment.
double mean_radiance_towards(const scenes::Scene& scene, const glm::vec3& eye, const glm::vec3& forward) {
  std::unique_ptr<render::EnvironmentLight> sky;
  if (scene.environment)
    sky = std::make_unique<render::EnvironmentLight>(read_image(scene.environment->path), scene.environment->scale);
  const render::RenderScene rs(scene, std::move(sky));
  render::CameraModel camera;
  camera.projection = render::Projection::Perspective;
  camera.position = eye;
  camera.forward = forward;
  camera.yfov = 1.05f;
  camera.width = camera.height = 32;
  render::RenderSettings settings;
  settings.spp = 16;
  settings.aovs = false;
  settings.progress = false;
  const Image image = render::render_view(rs, camera, settings).film.color();
  double sum = 0.0;
  for (float v : image.pixels) sum += v;
  return sum / double(image.pixels.size());
}

std::string file_bytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

TEST(ApartmentRealLibrary, EveryRoomFurnishedAndNoMeshesCross) {
  if (!library_installed()) GTEST_SKIP() << "sweethome3d-furniture is not installed";
  for (uint64_t seed : {1u, 2u}) {
    const scenes::ApartmentPlan plan = scenes::plan_apartment(seed, 0, 6);
    scenes::AssetModelCache models;
    const scenes::ApartmentFurnishing f = scenes::furnish_apartment(plan, real_library(), models, ApartmentLighting::Night);
    std::vector<int> per_room(plan.rooms.size(), 0);
    for (const scenes::PlacedAsset& p : f.items)
      if (p.room >= 0) ++per_room[size_t(p.room)];
    for (size_t r = 0; r < plan.rooms.size(); ++r)
      EXPECT_GE(per_room[r], plan.rooms[r].type == scenes::RoomType::Corridor ? 1 : 3) << plan.rooms[r].name;
    // Every pair whose boxes overlap (chairs tucked under tables, objects on shelves) is
    // checked on the meshes.
    int overlapping = 0;
    for (size_t a = 0; a < f.items.size(); ++a)
      for (size_t b = a + 1; b < f.items.size(); ++b) {
        if (!f.items[a].bounds().overlaps(f.items[b].bounds(), 0.0f)) continue;
        ++overlapping;
        EXPECT_FALSE(scenes::pieces_interpenetrate(f.items[a], f.items[b], models))
            << f.items[a].role << " (" << f.items[a].entry->name << ") / " << f.items[b].role << " ("
            << f.items[b].entry->name << "), seed " << seed;
      }
    EXPECT_GT(overlapping, 0) << "no piece tucked or stacked: the mesh check was not exercised";
    for (const scenes::PlacedAsset& p : f.items) {
      if (p.entry->is_light()) {
        EXPECT_TRUE(p.lamp_on) << p.entry->name;
      }
    }
  }
}

// The crossing check can fail: a chair pushed into its table crosses it.
TEST(ApartmentRealLibrary, CrossingIsDetected) {
  if (!library_installed()) GTEST_SKIP() << "sweethome3d-furniture is not installed";
  const scenes::ApartmentPlan plan = scenes::plan_apartment(1, 0, 6);
  scenes::AssetModelCache models;
  const scenes::ApartmentFurnishing f = scenes::furnish_apartment(plan, real_library(), models, ApartmentLighting::Day);
  const scenes::PlacedAsset* table = nullptr;
  for (const scenes::PlacedAsset& p : f.items)
    if (p.role == "sofa") table = &p;
  ASSERT_NE(table, nullptr);
  scenes::PlacedAsset inside = *table;
  inside.position += glm::vec3(0.1f, 0.05f, 0.05f);  // the same sofa, shifted into itself
  EXPECT_TRUE(scenes::pieces_interpenetrate(*table, inside, models));
}

TEST(ApartmentRealLibrary, SameSeedSameBytesAndLampsLitAtNight) {
  if (!library_installed()) GTEST_SKIP() << "sweethome3d-furniture is not installed";
  const fs::path a = temp_dir("apartment_a"), b = temp_dir("apartment_b");
  scenes::ApartmentOptions night;
  night.lighting = ApartmentLighting::Night;
  night.rooms = 3;
  const scenes::ApartmentSummary sa = scenes::generate_apartment(a, 0, 7, real_library(), night);
  scenes::generate_apartment(b, 0, 7, real_library(), night);
  EXPECT_EQ(file_bytes(a / "apartment_0.gltf"), file_bytes(b / "apartment_0.gltf"));
  EXPECT_EQ(file_bytes(a / "apartment_0.bin"), file_bytes(b / "apartment_0.bin"));
  EXPECT_GE(sa.lamps_lit, 3u);  // a ceiling light per room at least
  const scenes::Scene scene = scenes::load_gltf(a / "apartment_0.gltf");
  EXPECT_GE(scene.lights.size(), sa.lamps_lit);
  EXPECT_FALSE(sa.attributions.empty());
}

// A view of a living-room window: brighter by day (sky and sun) than at night (lamps).
TEST(ApartmentRealLibrary, WindowsLetDaylightIn) {
  if (!library_installed()) GTEST_SKIP() << "sweethome3d-furniture is not installed";
  double mean[2] = {0.0, 0.0};
  for (int night = 0; night < 2; ++night) {
    const fs::path dir = temp_dir(night ? "apartment_night" : "apartment_day");
    scenes::ApartmentOptions options;
    options.lighting = night ? ApartmentLighting::Night : ApartmentLighting::Day;
    options.rooms = 2;
    scenes::generate_apartment(dir, 0, 3, real_library(), options);
    const scenes::Scene scene = scenes::load_gltf(dir / "apartment_0.gltf");
    const scenes::ApartmentPlan plan = scenes::plan_apartment(3, 0, 2);
    const scenes::WallOpening* window = nullptr;
    for (const scenes::WallOpening& o : plan.openings)
      if (o.kind == scenes::WallOpeningKind::Window && o.room == 0) window = &o;
    ASSERT_NE(window, nullptr);
    // From 1.2 m inside the window, looking at it.
    const glm::vec2 c = window->footprint.centre() - 1.2f * window->outward;
    const glm::vec3 eye(c.x, 0.5f * (window->bottom + window->top), c.y);
    mean[night] = mean_radiance_towards(scene, eye, glm::vec3(window->outward.x, 0.0f, window->outward.y));
  }
  EXPECT_GT(mean[0], 3.0 * mean[1]) << "day " << mean[0] << ", night " << mean[1];
}

// The direct irradiance at si from the emissive triangles above its facet, estimated both
// ways: light samples with their shadow rays, and cosine-distributed rays that hit a lamp.
struct BothWays {
  test::MeanAndError light, ray;
};

BothWays direct_irradiance_both_ways(const render::RenderScene& rs, const render::SurfaceInteraction& si,
                                     const glm::vec3& wo, render::Rng* rng) {
  constexpr int kSamples = 2000;
  // Light from above the facet, which both strategies can find (below it only the light
  // samples reach, through the smooth-surface lift, where the facet's neighbours allow).
  render::ShadingPoint x = render::shading_point(si, wo);
  x.frame = render::Frame(x.geometric_normal);
  render::DirectLightOptions cosine;
  cosine.lobes = render::Lobes::kCosine;
  cosine.mis = false;
  cosine.punctual = false;
  render::PathCounters counters;
  BothWays both;
  both.light = test::monte_carlo(kSamples, [&](int) {
    render::LightVariates u;
    u.select = rng->next_float();
    u.point = rng->next_2d();
    return double(luminance(render::sample_emitter_light(rs, x, u, cosine, glm::vec3(1.0f), rng, &counters)));
  });
  both.ray = test::monte_carlo(kSamples, [&](int) {
    const glm::vec3 w = x.frame.to_world(render::sample_cosine_hemisphere(rng->next_2d()));
    render::SurfaceInteraction hit;
    const bool lamp =
        rs.trace(render::Ray{render::spawn_origin(si.position, x.geometric_normal, w), w}, &hit) && hit.emits;
    return lamp ? double(kPi * luminance(hit.emission)) : 0.0;
  });
  return both;
}

// Next-event estimation and rays agree on what the lamps give the surfaces round them: at
// points a few centimetres from every lamp of a furnished night apartment (shades, fixtures,
// their plates and canopies, real meshes with smoothed normals), the direct irradiance from
// light samples with their shadow rays equals that from cosine-distributed rays that hit the
// lamps. Both strategies estimate one integral only if both see the same things: shadow rays
// leaving from a lifted point (a thin plate's normals smoothed over its rim lifted it by
// centimetres) or a sample of the point's own triangle broke that on the night apartment.
TEST(ApartmentRealLibrary, LightSamplesAndRaysSeeTheLampsAlike) {
  if (!library_installed()) GTEST_SKIP() << "sweethome3d-furniture is not installed";
  const fs::path dir = temp_dir("apartment_lamps");
  scenes::ApartmentOptions night;
  night.lighting = ApartmentLighting::Night;
  night.rooms = 3;
  scenes::generate_apartment(dir, 0, 1, real_library(), night);
  const scenes::Scene scene = scenes::load_gltf(dir / "apartment_0.gltf");
  const render::RenderScene rs(scene);
  render::Rng rng(11, 2);
  double sum_light = 0.0, sum_ray = 0.0, variance = 0.0;  // variance of sum_light - sum_ray
  int points = 0, far_apart = 0;
  for (const scenes::Mesh& mesh : scene.meshes) {
    if (!(glm::length(scene.materials[size_t(mesh.material)].emission()) > 0.0f) || mesh.triangles.empty()) continue;
    for (int k = 0; k < 48; ++k) {
      // A point a few centimetres from a random triangle of the lamp, in a random direction.
      const glm::uvec3 t = mesh.triangles[size_t(rng.next_float() * float(mesh.triangles.size())) % mesh.triangles.size()];
      const glm::vec3 centre = (mesh.positions[t.x] + mesh.positions[t.y] + mesh.positions[t.z]) / 3.0f;
      render::SurfaceInteraction si, back;
      const glm::vec3 d = render::sample_uniform_sphere(rng.next_2d());
      // Seen from the start, the lamp comes first (not the ceiling it is pressed against).
      if (!rs.trace(render::Ray{centre + 0.03f * d, -d}, &back) || !back.emits) continue;
      if (!rs.trace(render::Ray{centre + 0.03f * d, d}, &si) || si.distance > 0.3f || si.emits) continue;
      // Not the roof space above a ceiling: no probe sees it, and there the top of a canopy
      // pressed against the ceiling shares its plane (light samples reach it, rays do not).
      if (scene.meshes[size_t(si.mesh)].name.rfind("roof", 0) == 0) continue;
      const BothWays both = direct_irradiance_both_ways(rs, si, -d, &rng);
      const double light = both.light.mean, ray = both.ray.mean;
      sum_light += light;
      sum_ray += ray;
      variance += both.light.standard_error * both.light.standard_error + both.ray.standard_error * both.ray.standard_error;
      ++points;
      if (std::abs(light - ray) > 0.5 * std::max(light, ray) && std::max(light, ray) > 0.05) ++far_apart;
    }
  }
  const double sigma = std::sqrt(variance);
  std::printf("[lamps] %d points: light samples %.4f, rays %.4f (ratio %.4f, %.1f sigma), %d points over 50%% apart\n",
              points, sum_light, sum_ray, sum_light / sum_ray, (sum_light - sum_ray) / sigma, far_apart);
  ASSERT_GT(points, 20);
  ASSERT_GT(sum_ray, 0.0);
  EXPECT_NEAR(sum_light, sum_ray, 4.0 * sigma + 0.01 * sum_ray);
  EXPECT_LE(far_apart, 1) << "points whose two estimates differ by over half";
}

}  // namespace
}  // namespace phyir
