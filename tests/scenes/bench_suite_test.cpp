// The benchmark suite (bench_suite.h): written from the fixture furniture library and the
// checked-in Blender room, every scene loads, the bedroom view stands in a bedroom, and a
// broken suite.json is refused with its name.
#include <gtest/gtest.h>

#include <fstream>
#include <set>

#include "phyir/core/error.h"
#include "phyir/scenes/bench_suite.h"
#include "phyir/scenes/gltf_loader.h"

namespace phyir::scenes {
namespace {

namespace fs = std::filesystem;

const fs::path kData = fs::path(PHYIR_TEST_DATA_DIR);

fs::path fresh_dir(const std::string& name) {
  const fs::path dir = fs::path(::testing::TempDir()) / "phyir_bench_suite_test" / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

TEST(BenchSuite, EverySceneLoadsAndReadsBackAsWritten) {
  const fs::path dir = fresh_dir("suite");
  const SuiteSources sources{kData / "assets" / "fixture", kData / "gltf" / "blender_lit_room"};
  const std::vector<SuiteScene> written = write_bench_suite(dir, sources);
  ASSERT_EQ(written.size(), 6u);
  std::set<std::string> names;
  for (const SuiteScene& s : written) {
    names.insert(s.name);
    const Scene scene = load_gltf(s.scene);  // the schema check runs on every load
    EXPECT_FALSE(scene.meshes.empty()) << s.name;
    if (s.camera) {
      const glm::vec3 lo = scene.bounds.min, hi = scene.bounds.max;
      EXPECT_TRUE(glm::all(glm::greaterThan(*s.camera, lo)) && glm::all(glm::lessThan(*s.camera, hi))) << s.name;
    }
  }
  EXPECT_EQ(names.size(), written.size());
  const std::vector<SuiteScene> read = read_bench_suite(dir / "suite.json");
  ASSERT_EQ(read.size(), written.size());
  for (size_t k = 0; k < read.size(); ++k) {
    EXPECT_EQ(read[k].name, written[k].name);
    EXPECT_EQ(read[k].camera.has_value(), written[k].camera.has_value());
  }
}

TEST(BenchSuite, ABrokenSuiteIsRefusedWithItsName) {
  const fs::path dir = fresh_dir("broken");
  for (const std::string& text : {std::string("{"), std::string("{\"scenes\": []}"),
                                  std::string("{\"scenes\": [{\"name\": \"a\", \"scene\": \"missing.gltf\"}]}"),
                                  std::string("{\"scenes\": [{\"name\": \"../up\", \"scene\": \"x.gltf\"}]}")}) {
    std::ofstream(dir / "suite.json") << text;
    try {
      read_bench_suite(dir / "suite.json");
      ADD_FAILURE() << "accepted: " << text;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("suite.json"), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace phyir::scenes
