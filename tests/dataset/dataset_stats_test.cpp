// dataset stats: a real tiny dataset whose view folders are then overwritten with maps of
// known content (a column pattern of pixel classes, a luminance ramp, clipped input
// columns, known timing.json), so every fraction, mean and percentile has an answer worked
// out by hand below; deterministic whatever the thread count; the contact sheet's layout and
// pixels; a clear error without a manifest.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "dataset_test_helpers.h"
#include "phyir/core/error.h"
#include "phyir/core/image_io.h"
#include "phyir/dataset/dataset_stats.h"
#include "phyir/dataset/layout.h"
#include "phyir/dataset/manifest.h"

namespace phyir::dataset {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

constexpr int kW = 64, kH = 32;  // the tiny preset

// Columns of a view (64 wide, every row alike unless said):
//   0-7 no geometry, 8-11 emissive, 12-15 transparent (R = 0, M = 1 there: must not count
//   as mirror or metal), 16-23 mirror R = 0.01 metal, 24-39 glossy R = 0.3 (column 24 exactly
//   0.05), metal in rows 0-15, 40-63 diffuse R = 0.8 (column 40 exactly 0.5; column 41 M =
//   exactly 0.5, not metal).
// color.exr is grey with luminance y + 1 in row y (1 .. 32); input.png is white in columns
// 0-15 (clipped), 0.5 elsewhere.
void write_known_view(const fs::path& dir, int k) {
  Image color(kW, kH, 3), geometry(kW, kH, 1), emissive(kW, kH, 1), transparent(kW, kH, 1);
  Image roughness(kW, kH, 1), metalness(kW, kH, 1), input(kW, kH, 3);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      for (int c = 0; c < 3; ++c) {
        color.at(x, y, c) = float(y + 1);
        input.at(x, y, c) = x < 16 ? 1.0f : 0.5f;
      }
      geometry.at(x, y) = x < 8 ? 0.0f : 1.0f;
      emissive.at(x, y) = x >= 8 && x < 12 ? 1.0f : 0.0f;
      transparent.at(x, y) = x >= 12 && x < 16 ? 1.0f : 0.0f;
      float r = 0, m = 1;
      if (x >= 16 && x < 24) r = 0.01f, m = 1;
      else if (x >= 24 && x < 40) r = x == 24 ? 0.05f : 0.3f, m = y < 16 ? 1.0f : 0.0f;
      else if (x >= 40) r = x == 40 ? 0.5f : 0.8f, m = x == 41 ? 0.5f : 0.0f;
      roughness.at(x, y) = r;
      metalness.at(x, y) = m;
    }
  write_image(dir / "color.exr", color);
  write_image(dir / "mask_geometry.exr", geometry);
  write_image(dir / "mask_emissive.exr", emissive);
  write_image(dir / "mask_transparent.exr", transparent);
  write_image(dir / "roughness.exr", roughness);
  write_image(dir / "metalness.exr", metalness);
  write_image(dir / "input.png", input);
  const json timing = {{"view_seconds", 10.0 + k},
                       {"timings", {{"color_seconds", 4.0 + k}, {"probe_seconds", 5.0}}},
                       {"settings", {{"threads", 2}}}};
  write_file_atomic(dir / kTimingFile, timing.dump(2));
}

class DatasetStatsTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = test::fresh_test_dir();
    const fs::path rooms = test::make_rooms(dir_, 2);
    DatasetSettings s = test::tiny_settings(2);
    s.split = {0.5, 0.25, 0.25};
    test::generate(rooms, data(), s);
    manifest_ = read_manifest(data());
    for (size_t k = 0; k < manifest_.views.size(); ++k)
      write_known_view(data() / manifest_.views[k]["dir"].get<std::string>(), int(k));
  }
  fs::path data() const { return dir_ / "data"; }
  fs::path dir_;
  Manifest manifest_;
};

TEST_F(DatasetStatsTest, MaterialMixLightAndCostOfKnownViews) {
  StatsOptions o;
  o.threads = 2;
  o.progress = false;
  const DatasetStats st = compute_dataset_stats(data(), o);
  ASSERT_EQ(manifest_.views.size(), 4u);
  EXPECT_EQ(st.views, 4u);
  EXPECT_EQ(st.scenes, 2u);
  EXPECT_EQ(st.views_measured, 4u);
  EXPECT_EQ(st.width, kW);
  EXPECT_EQ(st.preset, "tiny");

  // Splits and scenes, counted from the manifest here.
  std::map<std::string, size_t> per_split, per_scene;
  for (const json& v : manifest_.views) {
    ++per_split[v["split"].get<std::string>()];
    ++per_scene[v["scene"]["name"].get<std::string>()];
  }
  EXPECT_EQ(st.views_per_split, per_split);
  EXPECT_EQ(st.views_per_scene, per_scene);

  const MaterialCounts& m = st.material;
  ASSERT_EQ(m.pixels, 4u * kW * kH);
  const uint64_t per_column = 4u * kH;  // 4 views x 32 rows
  EXPECT_EQ(m.no_geometry, 8 * per_column);
  EXPECT_EQ(m.emissive, 4 * per_column);
  EXPECT_EQ(m.transparent, 4 * per_column);
  EXPECT_EQ(m.mirror, 8 * per_column);
  EXPECT_EQ(m.glossy, 16 * per_column);
  EXPECT_EQ(m.diffuse, 24 * per_column);
  EXPECT_EQ(m.metal, 8 * per_column + 16 * per_column / 2);
  EXPECT_DOUBLE_EQ(m.fraction(m.metal), 0.25);
  EXPECT_DOUBLE_EQ(m.fraction(m.mirror), 0.125);

  // Luminance y + 1 in row y: mean 16.5; the p-th percentile is the first row value v with
  // v / 32 >= p: p1 -> 1, p5 -> 2, p50 -> 16, p95 -> 31, p99 -> 32 (histogram: 1.2 %).
  EXPECT_NEAR(st.luminance_mean, 16.5, 1e-9);
  EXPECT_NEAR(st.luminance_max, 32.0, 1e-6);
  const std::map<std::string, double> want = {{"p1", 1}, {"p5", 2}, {"p50", 16}, {"p95", 31}, {"p99", 32}};
  for (const auto& [name, value] : want) {
    ASSERT_TRUE(st.luminance_percentiles.count(name)) << name;
    EXPECT_NEAR(st.luminance_percentiles.at(name), value, 0.012 * value) << name;
  }
  EXPECT_DOUBLE_EQ(st.input_clipped, 0.25);
  double exposure = 0, rays = 0;
  for (const json& v : manifest_.views) {
    exposure += v["input"]["exposure_stops"].get<double>() / 4;
    rays += v["render"]["counters"]["rays_traced"].get<double>() / 4;
  }
  EXPECT_NEAR(st.exposure_stops.mean, exposure, 1e-6);
  EXPECT_NEAR(st.rays.mean, rays, 1e-6 * rays);
  EXPECT_EQ(st.probe_rays.count, 0u);  // no probes in this dataset

  // timing.json: 10, 11, 12, 13 s per view, colour 4 .. 7 s, probes 5 s.
  EXPECT_EQ(st.view_seconds.count, 4u);
  EXPECT_DOUBLE_EQ(st.view_seconds.mean, 11.5);
  EXPECT_DOUBLE_EQ(st.view_seconds.median, 11.5);
  EXPECT_DOUBLE_EQ(st.view_seconds.max, 13.0);
  EXPECT_DOUBLE_EQ(st.view_seconds.total, 46.0);
  EXPECT_DOUBLE_EQ(st.color_seconds.mean, 5.5);
  EXPECT_DOUBLE_EQ(st.probe_seconds.mean, 5.0);

  const std::string text = format_stats(st);
  EXPECT_THAT(text, ::testing::HasSubstr("metal         25.0 %"));
  EXPECT_THAT(text, ::testing::HasSubstr("mirror        12.5 %"));
  const json j = stats_to_json(st);
  EXPECT_DOUBLE_EQ(j["material"]["fractions"]["diffuse"].get<double>(), 24.0 / 64);
  EXPECT_EQ(j["views"], 4);
}

TEST_F(DatasetStatsTest, SameNumbersWhateverTheThreadsAndASampleReadsFewerViews) {
  StatsOptions one, two;
  one.threads = 1;
  two.threads = 2;
  one.progress = two.progress = false;
  EXPECT_EQ(stats_to_json(compute_dataset_stats(data(), one)).dump(),
            stats_to_json(compute_dataset_stats(data(), two)).dump());
  StatsOptions sample = two;
  sample.max_views = 2;
  const DatasetStats st = compute_dataset_stats(data(), sample);
  EXPECT_EQ(st.views_measured, 2u);
  EXPECT_EQ(st.material.pixels, 2u * kW * kH);
  EXPECT_EQ(st.views, 4u);  // counts still cover every view
  EXPECT_EQ(st.view_seconds.count, 4u);
}

TEST_F(DatasetStatsTest, ContactSheetLayoutAndThumbnails) {
  ContactSheetOptions o;
  o.count = 3;
  o.columns = 2;
  o.thumb_width = 32;  // thumbnails 32 x 16: input.png halved
  const fs::path out = dir_ / "sheet.png";
  write_contact_sheet(data(), out, o);
  const Image sheet = read_image(out);
  // pad 4, caption 18: 4 + 2 x (32 + 4) wide, 4 + 2 x (16 + 18 + 4) high.
  EXPECT_EQ(sheet.width, 76);
  EXPECT_EQ(sheet.height, 80);
  EXPECT_EQ(sheet.channels, 3);
  EXPECT_NEAR(sheet.at(0, 0), 0.12, 0.01);  // background
  for (const auto& [x0, y0] : std::vector<std::pair<int, int>>{{4, 4}, {40, 4}, {4, 42}}) {
    EXPECT_NEAR(sheet.at(x0 + 2, y0 + 8, 1), 1.0, 0.01) << x0 << "," << y0;    // white input columns
    EXPECT_NEAR(sheet.at(x0 + 20, y0 + 8, 1), 0.5, 0.01) << x0 << "," << y0;   // grey columns
  }
  EXPECT_NEAR(sheet.at(56, 50), 0.12, 0.01);  // the fourth cell stays empty
  for (const auto& entry : fs::directory_iterator(dir_))
    EXPECT_FALSE(is_temporary_name(entry.path().filename().string())) << entry.path();
}

TEST(DatasetStats, NeedsAManifest) {
  const fs::path dir = test::fresh_test_dir();
  try {
    compute_dataset_stats(dir);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), ::testing::HasSubstr("manifest.json"));
  }
}

}  // namespace
}  // namespace phyir::dataset
