// Presets and validation, the JSON record of the settings (tidy floats, no paths or thread
// counts), and the network input's exposure: auto maps the percentile to the target,
// jitter is deterministic per view and bounded, fixed is fixed.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

#include "dataset_test_helpers.h"
#include "phyir/core/error.h"
#include "phyir/core/image_io.h"
#include "phyir/core/setting_error.h"
#include "phyir/dataset/input_image.h"
#include "phyir/dataset/settings.h"

namespace phyir::dataset {
namespace {

using ::testing::HasSubstr;

TEST(Settings, PresetsAreValidAndDistinct) {
  for (const std::string& name : preset_names()) {
    const DatasetSettings s = preset_settings(name);
    EXPECT_NO_THROW(s.validate()) << name;
    EXPECT_EQ(s.width, 2 * s.height) << name;
    EXPECT_EQ(s.preset, name);
  }
  const DatasetSettings tiny = preset_settings("tiny");
  EXPECT_EQ(tiny.width, 64);
  EXPECT_EQ(tiny.height, 32);
  EXPECT_EQ(tiny.spp, 4);
  const DatasetSettings paper = preset_settings("paper");
  EXPECT_EQ(paper.height, 256);
  EXPECT_EQ(paper.width, 512);
  EXPECT_EQ(paper.probe.layout.grid_height, 128);
  EXPECT_EQ(paper.probe.layout.grid_width, 256);
  EXPECT_EQ(paper.probe.layout.res_height, 16);
  EXPECT_EQ(paper.probe.layout.res_width, 32);
  EXPECT_THROW(preset_settings("huge"), Error);
}

TEST(Settings, ValidationNamesTheSetting) {
  const auto message = [](auto edit) {
    DatasetSettings s = preset_settings("tiny");
    edit(s);
    try {
      s.validate();
    } catch (const SettingError& e) {
      return std::string(e.what());
    }
    return std::string("(accepted)");
  };
  EXPECT_THAT(message([](DatasetSettings& s) { s.width = 100; }), HasSubstr("size: 100x32"));
  EXPECT_THAT(message([](DatasetSettings& s) { s.spp = 0; }), HasSubstr("spp: 0"));
  EXPECT_THAT(message([](DatasetSettings& s) { s.views_per_scene = 0; }), HasSubstr("views_per_scene: 0"));
  EXPECT_THAT(message([](DatasetSettings& s) { s.split = {0.5, 0.2, 0.2}; }), HasSubstr("split: 0.5,0.2,0.2"));
  EXPECT_THAT(message([](DatasetSettings& s) { s.input.view = "Filmic"; }), HasSubstr("input.view: 'Filmic'"));
  EXPECT_THAT(message([](DatasetSettings& s) { s.input.jitter_stops = -1; }), HasSubstr("input.jitter_stops: -1"));
}

TEST(Settings, JsonRecordsTidyNumbersAndNoPaths) {
  const nlohmann::json j = preset_settings("tiny").to_json();
  EXPECT_EQ(j["input"]["percentile"].dump(), "0.95");
  EXPECT_EQ(j["viewpoints"]["clearance_m"].dump(), "0.3");
  EXPECT_EQ(j["render"]["width"], 64);
  EXPECT_EQ(j["input"]["ocio_config_sha256"].get<std::string>().size(), 64u);
  const std::string text = j.dump();
  EXPECT_EQ(text.find("threads"), std::string::npos);
  EXPECT_EQ(text.find("/work"), std::string::npos);
  EXPECT_EQ(tidy_floats(j), j);  // idempotent
  EXPECT_TRUE(preset_settings("tiny").to_json()["probes"].is_object());
  DatasetSettings no_probes = preset_settings("tiny");
  no_probes.probes = false;
  EXPECT_TRUE(no_probes.to_json()["probes"].is_null());
}

Image ramp(int n) {
  Image image(n, 1, 3);
  for (int i = 0; i < n; ++i)
    for (int c = 0; c < 3; ++c) image.at(i, 0, c) = float(i + 1);  // values 1..n, each three times
  return image;
}

TEST(InputExposure, AutoMapsThePercentileToTheTarget) {
  InputSettings in;  // auto, 0.95, 0.9
  const InputExposure e = choose_input_exposure(ramp(100), in, 7);
  // 300 values; index floor(0.95 * 300) = 285 of the sorted list is the value 96.
  ASSERT_TRUE(e.percentile_value.has_value());
  EXPECT_FLOAT_EQ(float(*e.percentile_value), 96.0f);
  EXPECT_NEAR(e.stops, std::log2(0.9 / 96.0), 1e-5);
  EXPECT_EQ(e.jitter_stops, 0.0f);
  // A black image: 0 stops, not infinity.
  EXPECT_EQ(choose_input_exposure(Image(4, 2, 3, 0.0f), in, 7).stops, 0.0f);
}

TEST(InputExposure, JitterIsDeterministicPerViewAndBounded) {
  InputSettings in;
  in.jitter_stops = 0.5f;
  double lo = 1, hi = -1;
  for (uint64_t seed = 0; seed < 500; ++seed) {
    const InputExposure e = choose_input_exposure(ramp(10), in, seed);
    EXPECT_EQ(e.stops, choose_input_exposure(ramp(10), in, seed).stops);
    EXPECT_LE(std::abs(e.jitter_stops), 0.5f);
    EXPECT_EQ(float(e.stops), float(e.base_stops) + float(e.jitter_stops));  // summed in float, as recorded
    lo = std::min(lo, double(e.jitter_stops));
    hi = std::max(hi, double(e.jitter_stops));
  }
  EXPECT_LT(lo, -0.4);
  EXPECT_GT(hi, 0.4);
  in.auto_exposure = false;
  in.exposure_stops = -1.5f;
  in.jitter_stops = 0.0f;
  EXPECT_EQ(choose_input_exposure(ramp(10), in, 3).stops, -1.5f);
}

TEST(InputExposure, InputPngIsTheExposedColourThroughOcio) {
  const auto dir = test::fresh_test_dir();
  Image color(8, 4, 3, 0.25f);
  InputSettings in;
  in.auto_exposure = false;
  in.exposure_stops = 1.0f;  // 0.25 * 2 = 0.5 linear
  write_input_image(dir / "input.png", color, choose_input_exposure(color, in, 0), in);
  const Image png = read_image(dir / "input.png");
  ASSERT_EQ(png.channels, 3);
  // sRGB encoding of 0.5 is 0.7354; 8 bits.
  EXPECT_NEAR(png.at(3, 2, 1), 0.7354f, 1.0f / 255.0f);
}

}  // namespace
}  // namespace phyir::dataset
