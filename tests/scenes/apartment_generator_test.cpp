// generate_apartment() on the tiny fixture library (tests/data/assets/fixture): what a library
// has is placed and written, what it lacks is skipped and reported, the file loads back
// through the schema check, and the same seed gives the same bytes.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "phyir/scenes/apartment_generator.h"
#include "phyir/scenes/gltf_loader.h"

namespace phyir::scenes {
namespace {

namespace fs = std::filesystem;

const fs::path kFixture = fs::path(PHYIR_TEST_DATA_DIR) / "assets" / "fixture" / "PhyirFixture.sh3f";

fs::path fresh_dir(const std::string& name) {
  const fs::path dir = fs::path(::testing::TempDir()) / "phyir_apartment_generator_test" / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

std::string bytes_of(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

bool has(const std::vector<std::string>& v, const std::string& s) { return std::find(v.begin(), v.end(), s) != v.end(); }

TEST(ApartmentGenerator, FixtureLibraryFurnishesWhatItHasAndNamesWhatItLacks) {
  const AssetLibrary library = AssetLibrary::open(kFixture);
  ApartmentOptions options;
  options.rooms = 2;  // a living room without a kitchen: it gets the dining set
  options.lighting = ApartmentLighting::Day;
  options.portals = true;
  const fs::path a = fresh_dir("a"), b = fresh_dir("b");
  const ApartmentSummary s = generate_apartment(a, 0, 5, library, options);
  generate_apartment(b, 0, 5, library, options);
  EXPECT_EQ(bytes_of(a / "apartment_0.gltf"), bytes_of(b / "apartment_0.gltf"));
  EXPECT_EQ(bytes_of(a / "apartment_0.bin"), bytes_of(b / "apartment_0.bin"));
  EXPECT_TRUE(fs::exists(a / "apartment_0_sky.exr"));
  // The fixture has no sofa, bed or door, and its chair has a French name: skipped, listed,
  // the doorways left open.
  EXPECT_TRUE(has(s.missing_roles, "sofa"));
  EXPECT_TRUE(has(s.missing_roles, "dining_chair"));
  EXPECT_TRUE(has(s.missing_roles, "bed"));
  EXPECT_TRUE(has(s.missing_roles, "door"));
  EXPECT_FALSE(has(s.missing_roles, "window"));
  EXPECT_FALSE(s.attributions.empty());

  const Scene scene = load_gltf(a / "apartment_0.gltf");  // the schema check runs on every load
  ASSERT_TRUE(scene.environment.has_value());
  ASSERT_EQ(scene.lights.size(), 1u);  // the sun
  EXPECT_EQ(scene.lights[0].type, PunctualLight::Type::Directional);
  EXPECT_FALSE(scene.candidate_viewpoints.empty());
  size_t tables = 0, windows = 0;
  for (const Mesh& m : scene.meshes) {
    tables += m.name.rfind("dining_table_", 0) == 0;
    windows += m.name.rfind("window_", 0) == 0;
  }
  EXPECT_GT(tables, 0u);
  EXPECT_GT(windows, 0u);
  // Every window to the outside is a light portal facing into the apartment: a step inwards
  // from its centre is inside the scene's bounds, a step outwards is not.
  ASSERT_FALSE(scene.portals.empty());
  for (const Portal& p : scene.portals) {
    const glm::vec3 centre = p.corner + 0.5f * (p.edge_u + p.edge_v);
    const glm::vec3 inward = glm::normalize(glm::cross(p.edge_u, p.edge_v));
    auto inside = [&](const glm::vec3& q) {
      return glm::all(glm::greaterThan(q, scene.bounds.min)) && glm::all(glm::lessThan(q, scene.bounds.max));
    };
    EXPECT_TRUE(inside(centre + 0.5f * inward));
    EXPECT_FALSE(inside(centre - 0.5f * inward));
  }
}

TEST(ApartmentGenerator, NightHasNoSkyAndDayAndNightShareTheFurniture) {
  const AssetLibrary library = AssetLibrary::open(kFixture);
  ApartmentOptions day, night;
  day.rooms = night.rooms = 3;
  day.lighting = ApartmentLighting::Day;
  night.lighting = ApartmentLighting::Night;
  const fs::path d = fresh_dir("day"), n = fresh_dir("night");
  const ApartmentSummary sd = generate_apartment(d, 0, 9, library, day);
  const ApartmentSummary sn = generate_apartment(n, 0, 9, library, night);
  EXPECT_FALSE(fs::exists(n / "apartment_0_sky.exr"));
  EXPECT_FALSE(load_gltf(n / "apartment_0.gltf").environment.has_value());
  EXPECT_EQ(sd.pieces, sn.pieces);
  EXPECT_EQ(sd.files.triangles, sn.files.triangles);
  // rooms.json's count of glowing meshes is what the loader finds (lamp shades, by night only;
  // the real library's are counted in apartment_real_library_test).
  auto glowing = [](const Scene& scene) {
    size_t n = 0;
    for (const Mesh& m : scene.meshes) n += m.material >= 0 && scene.materials[size_t(m.material)].is_emissive();
    return n;
  };
  EXPECT_EQ(sd.files.emissive_meshes, 0u);
  EXPECT_EQ(sn.files.emissive_meshes, glowing(load_gltf(n / "apartment_0.gltf")));
}

}  // namespace
}  // namespace phyir::scenes
