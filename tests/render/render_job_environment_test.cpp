// The render job's environment: a scene's extras.phyir.environment lights the view when no
// --environment is given, --environment overrides it, render.json says which was used, and a
// missing or unreadable map fails naming the glTF file.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>

#include "phyir/core/atomic_file.h"
#include "phyir/core/error.h"
#include "phyir/core/image_io.h"
#include "phyir/render/render_job.h"
#include "phyir/scenes/gltf_writer.h"
#include "phyir/scenes/sky.h"

namespace phyir::render {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

fs::path fresh_dir() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const fs::path dir = fs::path(::testing::TempDir()) / "phyir_render_test" /
                       (std::string(info->test_suite_name()) + "." + info->name());
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// A grey floor under a camera, written twice: "plain.gltf" and "sky.gltf", whose scene
// declares "sky.exr" (a Preetham sky) at `scale`. Also "grey.exr", a constant environment.
void write_scenes(const fs::path& dir, float scale = 1.0f) {
  scenes::SkyParameters sky;
  sky.sun_elevation = 0.5;
  write_image(dir / "sky.exr", scenes::sky_image(scenes::PreethamSky(sky), 32));
  write_image(dir / "grey.exr", Image(8, 4, 3, 0.5f));
  scenes::GltfDocument doc;
  doc.generator = "render job test";
  scenes::GltfMaterial grey;
  grey.name = "grey";
  grey.base_color_factor = glm::vec4(0.5f, 0.5f, 0.5f, 1.0f);
  grey.metallic_factor = 0.0f;
  doc.materials.push_back(grey);
  scenes::GltfMesh floor;
  floor.name = "floor";
  floor.material = 0;
  floor.positions = {{-2, 0, -2}, {-2, 0, 2}, {2, 0, 2}, {2, 0, -2}};
  floor.normals.assign(4, glm::vec3(0, 1, 0));
  floor.indices = {0, 1, 2, 0, 2, 3};
  doc.meshes.push_back(floor);
  doc.cameras.push_back({"camera", {0.0f, 1.0f, 0.0f}, {0, 0, 0, 1}, 1.2f, 0.01f});
  scenes::write_gltf(dir / "plain.gltf", doc);
  doc.environment = scenes::GltfEnvironment{"sky.exr", {}, scale};  // already in place
  scenes::write_gltf(dir / "sky.gltf", doc);
}

RenderJob job(const fs::path& scene, const fs::path& out) {
  RenderJob j;
  j.scene_path = scene;
  j.out_dir = out;
  j.width = 16;
  j.height = 8;
  j.settings.spp = 4;
  j.settings.aovs = false;
  j.settings.progress = false;
  j.threads = 1;
  return j;
}

double mean(const fs::path& exr) {
  const Image image = read_image(exr);
  double sum = 0.0;
  for (float v : image.pixels) sum += v;
  return sum / double(image.pixels.size());
}

nlohmann::json settings(const fs::path& out) { return nlohmann::json::parse(read_file(out / "render.json"))["settings"]; }

TEST(RenderJobEnvironment, TheScenesEnvironmentLightsTheView) {
  const fs::path dir = fresh_dir();
  write_scenes(dir);
  const RenderReport lit = run_render_job(job(dir / "sky.gltf", dir / "lit"));
  run_render_job(job(dir / "plain.gltf", dir / "dark"));
  EXPECT_GT(mean(dir / "lit" / "color.exr"), 0.1);
  EXPECT_EQ(mean(dir / "dark" / "color.exr"), 0.0);  // no light at all
  EXPECT_EQ(lit.environment.source, "scene");
  EXPECT_EQ(settings(dir / "lit")["environment_source"], "scene");
  EXPECT_EQ(settings(dir / "lit")["environment"], (dir / "sky.exr").string());
  EXPECT_EQ(settings(dir / "dark")["environment_source"], "none");
  EXPECT_EQ(settings(dir / "dark")["environment"], "");
}

TEST(RenderJobEnvironment, TheFlagOverridesTheScenesEnvironment) {
  const fs::path dir = fresh_dir();
  write_scenes(dir);
  RenderJob overridden = job(dir / "sky.gltf", dir / "overridden");
  overridden.environment_path = dir / "grey.exr";
  run_render_job(overridden);
  RenderJob grey = job(dir / "plain.gltf", dir / "grey");
  grey.environment_path = dir / "grey.exr";
  run_render_job(grey);
  EXPECT_EQ(read_file(dir / "overridden" / "color.exr"), read_file(dir / "grey" / "color.exr"));
  EXPECT_EQ(settings(dir / "overridden")["environment_source"], "file");
  EXPECT_EQ(settings(dir / "overridden")["environment"], (dir / "grey.exr").string());
}

TEST(RenderJobEnvironment, ScalesMultiply) {
  const fs::path dir = fresh_dir();
  write_scenes(dir, 2.0f);
  RenderJob doubled = job(dir / "sky.gltf", dir / "doubled");
  doubled.environment_scale = 1.5f;
  const RenderReport report = run_render_job(doubled);
  EXPECT_EQ(report.environment.scale, 3.0f);
  EXPECT_EQ(settings(dir / "doubled")["environment_scale"], 3.0);
}

std::string render_error(const RenderJob& j) {
  try {
    run_render_job(j);
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(RenderJobEnvironment, AMissingOrUnreadableMapNamesTheGltfFile) {
  const fs::path dir = fresh_dir();
  write_scenes(dir);
  write_file_atomic(dir / "sky.exr", "not an image");
  EXPECT_THAT(render_error(job(dir / "sky.gltf", dir / "out")),
              HasSubstr("sky.gltf: environment 'sky.exr' (scene extras.phyir.environment): "));
  fs::remove(dir / "sky.exr");
  EXPECT_THAT(render_error(job(dir / "sky.gltf", dir / "out")),
              HasSubstr("sky.gltf: scene 0 extras.phyir.environment uri 'sky.exr' not found"));
}

}  // namespace
}  // namespace phyir::render
