// FutureHouse interchange: our data through export and import comes back to the files'
// precision, the published loader's conventions read our export (futurehouse_reader.py), and
// a release-style folder (no phyir sidecar) imports as the loader would read it.
#include <cmath>
#include <cstdlib>

#include <nlohmann/json.hpp>

#include "dataset_test_helpers.h"
#include "phyir/core/error.h"
#include "phyir/core/equirect.h"
#include "phyir/core/image_io.h"
#include "phyir/dataset/futurehouse.h"
#include "phyir/dataset/futurehouse_layout.h"
#include "phyir/dataset/manifest.h"
#include "phyir/dataset/verify.h"

namespace phyir::dataset::test {
namespace {

namespace fh = futurehouse;
using nlohmann::json;

// Radiance RGBE keeps 8 bits of mantissa for the largest channel of a pixel.
constexpr float kRgbeRelative = 1.0f / 128.0f;

// The largest |a - b| over pixels, each divided by (max channel of b's pixel + floor).
float worst_relative(const Image& a, const Image& b, float floor) {
  EXPECT_EQ(a.width, b.width);
  EXPECT_EQ(a.height, b.height);
  EXPECT_EQ(a.channels, b.channels);
  float worst = 0.0f;
  for (int y = 0; y < b.height; ++y)
    for (int x = 0; x < b.width; ++x) {
      float scale = 0.0f;
      for (int c = 0; c < b.channels; ++c) scale = std::max(scale, std::abs(b.at(x, y, c)));
      for (int c = 0; c < b.channels; ++c)
        worst = std::max(worst, std::abs(a.at(x, y, c) - b.at(x, y, c)) / (scale + floor));
    }
  return worst;
}

float worst_absolute(const Image& a, const Image& b) {
  EXPECT_EQ(a.pixels.size(), b.pixels.size());
  float worst = 0.0f;
  for (size_t i = 0; i < std::min(a.pixels.size(), b.pixels.size()); ++i)
    worst = std::max(worst, std::abs(a.pixels[i] - b.pixels[i]));
  return worst;
}

// A tiny dataset with probes and a fixed input exposure, made once for the suite.
class FutureHouseRoundTrip : public ::testing::Test {
 protected:
  static fs::path root_;
  static fs::path ours_, exported_, imported_;

  static void SetUpTestSuite() {
    root_ = fs::temp_directory_path() / ("phyir_futurehouse_test_" + std::to_string(::getpid()));
    fs::remove_all(root_);
    fs::create_directories(root_);
    DatasetSettings s = tiny_settings(2, true);
    s.input.auto_exposure = false;
    s.input.exposure_stops = 0.0f;
    ours_ = root_ / "ours";
    generate(make_rooms(root_, 2), ours_, s);
    exported_ = root_ / "exported";
    FutureHouseExportOptions e;
    e.dataset = ours_;
    e.out = exported_;
    e.threads = 2;
    e.progress = false;
    export_futurehouse(e);
    imported_ = root_ / "imported";
    FutureHouseImportOptions i;
    i.src = exported_;
    i.out = imported_;
    i.input.auto_exposure = false;
    i.threads = 2;
    i.progress = false;
    import_futurehouse(i);
  }
  static void TearDownTestSuite() { fs::remove_all(root_); }
};
fs::path FutureHouseRoundTrip::root_, FutureHouseRoundTrip::ours_, FutureHouseRoundTrip::exported_,
    FutureHouseRoundTrip::imported_;

TEST(FutureHouseLayout, PathsAndEncodingsFollowThePublishedLoader) {
  EXPECT_EQ(fh::map_path("R", "123_ai_training", 4, fh::Map::Normal).generic_string(),
            "R/KePanoData/123_ai_training/ue4_result/CubemapData/4_normal.hdr");
  EXPECT_EQ(fh::light_path("R", "p", 0).generic_string(), "R/KePanoLight/p/ue4_result/LightProbeData/0_light.exr");
  EXPECT_FLOAT_EQ(fh::decode_depth(0.4f), 2.0f);  // value * 10 / 2
  EXPECT_FLOAT_EQ(fh::encode_depth(2.0f), 0.4f);
  EXPECT_FLOAT_EQ(fh::decode_normal(1.0f), 1.0f);  // 2 v - 1
  EXPECT_FLOAT_EQ(fh::decode_normal(0.5f), 0.0f);
  EXPECT_FLOAT_EQ(fh::encode_normal(-1.0f), 0.0f);
}

TEST(FutureHouseLayout, NormalAxesParseInvertAndRefuse) {
  const fh::NormalAxes identity = fh::NormalAxes::parse("x,y,z");
  EXPECT_EQ(identity.name(), "x,y,z");
  const fh::NormalAxes turned = fh::NormalAxes::parse("-z,y,x");
  EXPECT_EQ(turned.name(), "-z,y,x");
  const glm::vec3 theirs(0.2f, 0.3f, 0.9f);
  const glm::vec3 ours = turned.to_ours(theirs);
  EXPECT_FLOAT_EQ(ours.x, -0.9f);
  EXPECT_FLOAT_EQ(ours.y, 0.3f);
  EXPECT_FLOAT_EQ(ours.z, 0.2f);
  const glm::vec3 back = turned.to_theirs(ours);
  EXPECT_FLOAT_EQ(back.x, theirs.x);
  EXPECT_FLOAT_EQ(back.z, theirs.z);
  for (const char* bad : {"x,y", "x,x,z", "x,y,w", "x,y,z,x", ""}) EXPECT_THROW(fh::NormalAxes::parse(bad), Error) << bad;
}

TEST_F(FutureHouseRoundTrip, ExportHasTheLoadersLayout) {
  const Manifest m = read_manifest(ours_);
  const json split = json::parse(read_file(exported_ / "split.json"));
  size_t plans = 0;
  for (const json& s : m.scenes) {
    const std::string plan = s["name"];
    EXPECT_NE(std::find(split[s["split"].get<std::string>()].begin(), split[s["split"].get<std::string>()].end(), plan),
              split[s["split"].get<std::string>()].end());
    size_t files = 0;
    for (const auto& entry : fs::directory_iterator(fh::maps_folder(exported_, plan))) files += entry.is_regular_file();
    EXPECT_EQ(files, 2u * fh::kMapsPerView) << plan;  // the loader counts 7 files per view
    for (int i = 0; i < 2; ++i) EXPECT_TRUE(fs::is_regular_file(fh::light_path(exported_, plan, i)));
    ++plans;
  }
  EXPECT_EQ(plans, 2u);
  EXPECT_FALSE(fs::exists(exported_.string() + ".partial"));
  const Image image = read_image(fh::map_path(exported_, m.scenes[0]["name"], 0, fh::Map::Image));
  EXPECT_EQ(image.channels, 3);
  EXPECT_EQ(image.width, 64);
}

TEST_F(FutureHouseRoundTrip, ImportOfTheExportVerifiesAndKeepsTheSplits) {
  const VerifyReport report = verify_dataset(imported_, 2);
  for (const std::string& p : report.problems) ADD_FAILURE() << p;
  EXPECT_EQ(report.views, 4u);
  const Manifest a = read_manifest(ours_), b = read_manifest(imported_);
  ASSERT_EQ(a.views.size(), b.views.size());
  for (size_t i = 0; i < a.views.size(); ++i) {
    EXPECT_EQ(a.views[i]["id"], b.views[i]["id"]);
    EXPECT_EQ(a.views[i]["split"], b.views[i]["split"]);
  }
  EXPECT_EQ(a.settings["probes"]["grid"], b.settings["probes"]["grid"]);
  EXPECT_EQ(a.settings["probes"]["resolution"], b.settings["probes"]["resolution"]);
  EXPECT_EQ(b.views_per_scene(), 2);
}

TEST_F(FutureHouseRoundTrip, MapsComeBackToTheFilesPrecision) {
  const Manifest m = read_manifest(ours_);
  for (const json& v : m.views) {
    const fs::path a = ours_ / v["dir"].get<std::string>(), b = imported_ / v["dir"].get<std::string>();
    SCOPED_TRACE(v["id"].get<std::string>());
    for (const char* name : {"color.exr", "basecolor.exr", "roughness.exr", "metalness.exr", "depth.exr"})
      EXPECT_LE(worst_relative(read_image(b / name), read_image(a / name), 1e-20f), kRgbeRelative) << name;
    // (n + 1) / 2 through RGBE, then normalised: a component moves by at most 2/128.
    EXPECT_LE(worst_absolute(read_image(b / "normal.exr"), read_image(a / "normal.exr")), 2.0f / 128.0f);
    for (const char* name : {"mask_geometry.exr", "mask_emissive.exr", "mask_transparent.exr", "probes.exr",
                             "probe_mask.exr"})
      EXPECT_EQ(read_image(b / name).pixels, read_image(a / name).pixels) << name;  // exact
    // input.png at the same fixed exposure from RGBE colour: a few 8-bit codes at most.
    EXPECT_LE(worst_absolute(read_image(b / "input.png"), read_image(a / "input.png")), 3.0f / 255.0f);
  }
}

TEST_F(FutureHouseRoundTrip, PythonReaderOfTheLoadersConventionsReadsTheExport) {
  if (!fs::exists("/usr/bin/python3")) GTEST_SKIP() << "no /usr/bin/python3";
  const std::string script = std::string(PHYIR_SOURCE_ROOT) + "/tests/dataset/futurehouse_reader.py";
  const std::string log = (root_ / "reader.log").string();
  const std::string command =
      "/usr/bin/python3 " + script + " " + exported_.string() + " " + ours_.string() + " > " + log + " 2>&1";
  EXPECT_EQ(std::system(command.c_str()), 0) << read_file(log);
  EXPECT_NE(read_file(log).find("read 4 views as the published loader would: OK"), std::string::npos) << read_file(log);
}

TEST_F(FutureHouseRoundTrip, ProbesFirstWritesOneLightFilePerPlan) {
  FutureHouseExportOptions e;
  e.dataset = ours_;
  e.out = root_ / "first";
  e.probes = ExportProbes::kFirst;
  e.progress = false;
  const FutureHouseExportSummary s = export_futurehouse(e);
  EXPECT_EQ(s.light_files, 2u);
  for (const json& scene : read_manifest(ours_).scenes) {
    size_t files = 0;
    for (const auto& entry : fs::directory_iterator(fh::light_folder(e.out, scene["name"]))) files += entry.is_regular_file();
    EXPECT_EQ(files, 1u);  // KePanoLighting skips a plan unless it holds exactly one
  }
  // Importing it: by default without probes (not every view has one); --probes only: view 0 of each plan.
  FutureHouseImportOptions i;
  i.src = e.out;
  i.out = root_ / "first_imported";
  i.probes = ImportProbes::kOnly;
  i.progress = false;
  const FutureHouseImportSummary imported = import_futurehouse(i);
  EXPECT_TRUE(imported.probes);
  EXPECT_EQ(imported.views, 2u);
  EXPECT_TRUE(verify_dataset(i.out, 2).ok());
  i.out = root_ / "first_auto";
  i.probes = ImportProbes::kAuto;
  const FutureHouseImportSummary automatic = import_futurehouse(i);
  EXPECT_FALSE(automatic.probes);
  EXPECT_EQ(automatic.views, 4u);
}

TEST_F(FutureHouseRoundTrip, RefusesAnExistingOutputFolder) {
  FutureHouseExportOptions e;
  e.dataset = ours_;
  e.out = exported_;
  e.progress = false;
  try {
    export_futurehouse(e);
    ADD_FAILURE() << "no error";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("exists already"), std::string::npos) << error.what();
  }
}

// A folder as the release ships it: no phyir/ sidecar, one mask, plans the loader skips.
class FutureHouseRelease : public ::testing::Test {
 protected:
  fs::path src;
  static constexpr int kW = 32, kH = 16;

  void SetUp() override {
    src = fresh_test_dir() / "release";
    write_plan("1_ai_training", 2, true);
    write_plan("2_ai_training", 1, false);
    fs::remove(fh::map_path(src, "2_ai_training", 0, fh::Map::Metallic));  // 6 files: the loader skips it
    write_file_atomic(src / "split.json",
                      R"({"train": ["1_ai_training", "2_ai_training"], "val": ["3_ai_training"], "test": []})");
  }

  // Upper half: a wall 2 m away facing the camera; lower half: floor (normal +Y) with a lamp
  // (mask 0) in its first column; the top row sees nothing (depth 0).
  void write_plan(const std::string& plan, int views, bool light_for_view0) {
    for (int i = 0; i < views; ++i) {
      Image image(kW, kH, 3, 0.25f), albedo(kW, kH, 3, 0.5f), roughness(kW, kH, 3, 0.1f), metallic(kW, kH, 3, 0.0f);
      Image mask(kW, kH, 3, 1.0f), normal(kW, kH, 3), depth(kW, kH, 3, fh::encode_depth(2.0f));
      for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
          const glm::vec3 d = equirect_direction({(x + 0.5f) / kW, (y + 0.5f) / kH});
          const glm::vec3 n = y < kH / 2 ? -d : glm::vec3(0, 1, 0);
          for (int c = 0; c < 3; ++c) normal.at(x, y, c) = fh::encode_normal(n[c]);
          if (y >= kH / 2 && x == 0)
            for (int c = 0; c < 3; ++c) mask.at(x, y, c) = 0.0f;
          if (y == 0)
            for (int c = 0; c < 3; ++c) depth.at(x, y, c) = 0.0f;
          roughness.at(x, y, 2) = 0.75f;  // the loader reads OpenCV's channel 0: the file's blue
        }
      const auto put = [&](fh::Map m, const Image& im) { write_image(fh::map_path(src, plan, i, m), im); };
      put(fh::Map::Image, image), put(fh::Map::Albedo, albedo), put(fh::Map::Roughness, roughness);
      put(fh::Map::Metallic, metallic), put(fh::Map::Mask, mask), put(fh::Map::Normal, normal), put(fh::Map::Depth, depth);
    }
    if (light_for_view0) write_image(fh::light_path(src, plan, 0), Image(4 * 32, 2 * 16, 3, 1.5f));  // 2 x 4 probes
  }

  FutureHouseImportOptions options(const std::string& out) const {
    FutureHouseImportOptions o;
    o.src = src;
    o.out = src.parent_path() / out;
    o.progress = false;
    o.threads = 2;
    return o;
  }
};

TEST_F(FutureHouseRelease, ImportsAsTheLoaderReadsIt) {
  const FutureHouseImportSummary s = import_futurehouse(options("imported"));
  EXPECT_EQ(s.plans, 1u);
  EXPECT_EQ(s.views, 2u);
  EXPECT_FALSE(s.probes);  // only view 0 has a light file
  ASSERT_EQ(s.left_out.size(), 2u);
  EXPECT_NE(s.left_out[0].find("2_ai_training"), std::string::npos);
  EXPECT_NE(s.left_out[0].find("6 files"), std::string::npos) << s.left_out[0];
  EXPECT_NE(s.left_out[1].find("3_ai_training: no folder"), std::string::npos) << s.left_out[1];
  EXPECT_GT(s.normals_facing_camera, 0.99);

  const fs::path out = src.parent_path() / "imported";
  EXPECT_TRUE(verify_dataset(out, 2).ok());
  const fs::path view = out / "views/1_ai_training/v001";
  const Image depth = read_image(view / "depth.exr"), geometry = read_image(view / "mask_geometry.exr");
  EXPECT_NEAR(depth.at(3, 5), 2.0f, 2.0f * kRgbeRelative);
  EXPECT_EQ(depth.at(3, 0), 0.0f);
  EXPECT_EQ(geometry.at(3, 0), 0.0f);
  EXPECT_EQ(geometry.at(3, 5), 1.0f);
  const Image normal = read_image(view / "normal.exr");
  EXPECT_NEAR(normal.at(5, 12, 1), 1.0f, 1e-3f);  // the floor's +Y
  EXPECT_EQ(normal.at(5, 0, 1), 0.0f);             // no surface, no normal
  const Image emissive = read_image(view / "mask_emissive.exr"), transparent = read_image(view / "mask_transparent.exr");
  EXPECT_EQ(emissive.at(0, 12), 1.0f);  // outside FutureHouse's mask: both, as the file does not say which
  EXPECT_EQ(transparent.at(0, 12), 1.0f);
  EXPECT_EQ(emissive.at(1, 12), 0.0f);
  EXPECT_NEAR(read_image(view / "roughness.exr").at(4, 4), 0.75f, 0.75f * kRgbeRelative);
}

TEST_F(FutureHouseRelease, ProbesOnlyTakesTheViewsWithALightFile) {
  FutureHouseImportOptions o = options("with_probes");
  o.probes = ImportProbes::kOnly;
  const FutureHouseImportSummary s = import_futurehouse(o);
  EXPECT_TRUE(s.probes);
  EXPECT_EQ(s.views, 1u);
  const Manifest m = read_manifest(o.out);
  EXPECT_EQ(m.settings["probes"]["grid"], json::array({2, 4}));
  EXPECT_EQ(m.settings["probes"]["resolution"], json::array({16, 32}));
  EXPECT_EQ(read_image(o.out / "views/1_ai_training/v000/probes.exr").pixels[7], 1.5f);
  EXPECT_TRUE(verify_dataset(o.out, 2).ok());
}

TEST_F(FutureHouseRelease, WrongNormalAxesShowInTheFacingFraction) {
  FutureHouseImportOptions o = options("turned");
  o.normal_axes = "-x,y,-z";  // half a turn about +Y: the walls face away (but for 3 rows near the top)
  EXPECT_LT(import_futurehouse(o).normals_facing_camera, 0.8);  // 11 of 15 rows; the floor still faces up
}

TEST_F(FutureHouseRelease, ErrorsNameTheFileAndTheProblem) {
  const auto message = [&](FutureHouseImportOptions o) {
    try {
      import_futurehouse(o);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  FutureHouseImportOptions o = options("x");
  o.split_file = src / "missing.json";
  EXPECT_NE(message(o).find("missing.json: no split file"), std::string::npos) << message(o);
  write_file_atomic(src / "bad.json", R"({"training": ["1_ai_training"]})");
  o.split_file = src / "bad.json";
  EXPECT_NE(message(o).find("bad.json: split \"training\" is not train, val or test"), std::string::npos) << message(o);
  o = options("x");
  o.src = src / "nowhere";
  EXPECT_NE(message(o).find("no KePanoData folder"), std::string::npos) << message(o);
  EXPECT_FALSE(fs::exists(src.parent_path() / "x"));
  EXPECT_FALSE(fs::exists(src.parent_path() / "x.partial"));
}

}  // namespace
}  // namespace phyir::dataset::test
