// Exposure-consistent targets (model/src/data/exposure.h): the sRGB curve equals OpenColorIO's;
// view.json's exposure is read (and its absence handled as documented); a view whose scene is
// 4x brighter, auto-exposed by the dataset's own code, gives the same input and the same
// targets in input units; the rendering layer on a dataset view's ground truth reproduces
// input.png's linear image in input units (and not in absolute ones).
#include <fstream>

#include "data.h"
#include "exposure.h"
#include "phyir/core/colour.h"
#include "phyir/core/error.h"
#include "phyir/core/image_io.h"
#include "phyir/dataset/input_image.h"
#include "phyir/view/view_record.h"
#include "render_layer.h"
#include "tiny_dataset.h"

namespace pm = phyir::model;
namespace fs = std::filesystem;
namespace F = torch::nn::functional;

namespace {

struct ThreadSetup {
  ThreadSetup() { torch::set_num_threads(1); }
} thread_setup;

fs::path scratch(const std::string& name) {
  const fs::path p = fs::temp_directory_path() / ("phyir_model_exposure_" + std::to_string(::getpid())) / name;
  fs::remove_all(p);
  fs::create_directories(p);
  return p;
}

// The view folder's resolutions: input at its own size, the rendering grid = the probe grid.
pm::ModelConfig native(const fs::path& view) {
  const phyir::Image color = phyir::read_image(view / "color.exr");
  const phyir::Image pmask = phyir::read_image(view / "probe_mask.exr");
  const phyir::Image mosaic = phyir::read_image(view / "probes.exr");
  pm::ModelConfig c;
  c.input_height = color.height, c.input_width = color.width;
  c.render_height = pmask.height, c.render_width = pmask.width;
  c.probe_height = mosaic.height / pmask.height, c.probe_width = mosaic.width / pmask.width;
  return c;
}

double stops_of(const fs::path& view) { return phyir::view::read_view(view).input.stops; }

}  // namespace

TEST(ModelExposure, SrgbCurveMatchesOpenColorIO) {
  // Decode: every 8-bit code against core's OCIO decode.
  phyir::Image codes(256, 1, 3);
  for (int i = 0; i < 256; ++i)
    for (int c = 0; c < 3; ++c) codes.at(i, 0, c) = i / 255.0f;
  phyir::Image decoded = codes;
  phyir::srgb_to_linear(decoded);
  const torch::Tensor mine = pm::srgb_decode(pm::image_to_tensor(codes));
  EXPECT_TRUE(torch::allclose(mine, pm::image_to_tensor(decoded), 1e-5, 1e-7));
  // Encode: linear values (past 1 too: clipped) against the Standard view at 0 stops.
  phyir::Image linear(512, 1, 3);
  for (int i = 0; i < 512; ++i)
    for (int c = 0; c < 3; ++c) linear.at(i, 0, c) = std::pow(i / 400.0f, 2.0f);
  const torch::Tensor ocio = pm::image_to_tensor(phyir::linear_to_display(linear, 0.0f, "Standard"));
  EXPECT_TRUE(torch::allclose(pm::srgb_encode(pm::image_to_tensor(linear)), ocio, 1e-5, 1e-6));
  // Round trip.
  const torch::Tensor x = torch::linspace(0.0, 1.0, 1001);
  EXPECT_TRUE(torch::allclose(pm::srgb_decode(pm::srgb_encode(x)), x, 1e-5, 1e-7));
}

class ExposureOnDataset : public ::testing::Test {
 protected:
  void SetUp() override {
    if (tiny::dataset().root.empty() && tiny::dataset().error.empty()) GTEST_SKIP() << PHYIR_BINARY << " not built";
    ASSERT_TRUE(tiny::dataset().error.empty()) << tiny::dataset().error;
    view_ = tiny::dataset().view("train");
    ASSERT_FALSE(view_.empty());
  }
  fs::path view_;
};

TEST_F(ExposureOnDataset, SameViewAtTwoExposuresGivesTheSameTargets) {
  // The same view in a scene 4x brighter: color.exr and probes.exr x 4, exposed by the
  // dataset's own auto exposure and written by its own input writer.
  const fs::path bright = scratch("bright");
  for (const auto& f : fs::directory_iterator(view_)) fs::copy(f.path(), bright / f.path().filename());
  for (const char* name : {"color.exr", "probes.exr"}) {
    phyir::Image im = phyir::read_image(view_ / name);
    for (float& p : im.pixels) p *= 4.0f;
    phyir::write_image(bright / name, im);
  }
  const phyir::dataset::InputSettings settings;
  const phyir::Image color = phyir::read_image(bright / "color.exr");
  const phyir::dataset::InputExposure exposure = phyir::dataset::choose_input_exposure(color, settings, 0);
  EXPECT_NEAR(exposure.stops, stops_of(view_) - 2.0, 1e-5);
  fs::remove(bright / "input.png");
  phyir::dataset::write_input_image(bright / "input.png", color, exposure, settings);
  std::ofstream(bright / "view.json") << nlohmann::json({{"input", exposure.to_json()}}).dump();

  const pm::ModelConfig c = native(view_);
  const pm::ViewTensors a = pm::load_view(view_, c, phyir::view::RadianceUnits::kInput);
  const pm::ViewTensors b = pm::load_view(bright, c, phyir::view::RadianceUnits::kInput);
  EXPECT_LE((a.image - b.image).abs().max().item<float>(), 1.0f / 255 + 1e-6f);  // the same input (8-bit rounding)
  EXPECT_TRUE(torch::allclose(a.color_lo, b.color_lo, 1e-5, 1e-7));
  EXPECT_TRUE(torch::allclose(a.probes, b.probes, 1e-5, 1e-7));
  // In absolute units the targets differ by the factor 4 the input cannot show.
  const pm::ViewTensors abs_a = pm::load_view(view_, c), abs_b = pm::load_view(bright, c);
  EXPECT_TRUE(torch::allclose(abs_b.probes, 4.0 * abs_a.probes, 1e-6, 0));
  EXPECT_TRUE(torch::allclose(a.probes, abs_a.probes * std::exp2(stops_of(view_)), 1e-6, 0));
}

// The study switch (--target-units): absolute targets are the files' radiance, input-unit
// targets that times 2^exposure_stops of the view, and nothing else changes.
TEST_F(ExposureOnDataset, TargetUnitsSwitchScalesTheTargetsByTheExposure) {
  const double stops = stops_of(view_);
  ASSERT_GT(std::abs(stops), 0.1) << "a view at 0 stops cannot tell the units apart";
  pm::ModelConfig input = native(view_), absolute = native(view_);
  absolute.target_units = "absolute";
  ASSERT_EQ(pm::target_radiance(input), phyir::view::RadianceUnits::kInput);
  ASSERT_EQ(pm::target_radiance(absolute), phyir::view::RadianceUnits::kAbsolute);
  const pm::ViewTensors a = pm::load_view(view_, input, pm::target_radiance(input));
  const pm::ViewTensors b = pm::load_view(view_, absolute, pm::target_radiance(absolute));
  const double factor = std::exp2(stops);
  EXPECT_TRUE(torch::allclose(a.probes, b.probes * factor, 1e-6, 0));
  EXPECT_TRUE(torch::allclose(a.color_lo, b.color_lo * factor, 1e-6, 0));
  EXPECT_NEAR((a.probes.sum() / b.probes.sum()).item<double>(), factor, 1e-5 * factor);
  EXPECT_NEAR((a.color_lo.sum() / b.color_lo.sum()).item<double>(), factor, 1e-5 * factor);
  // The absolute targets are the files' values.
  EXPECT_TRUE(torch::equal(b.probes, pm::load_view(view_, input, phyir::view::RadianceUnits::kAbsolute).probes));
  // Input, maps and masks do not depend on the unit.
  for (auto m : {&pm::ViewTensors::image, &pm::ViewTensors::depth, &pm::ViewTensors::normal,
                 &pm::ViewTensors::base_color, &pm::ViewTensors::render_mask, &pm::ViewTensors::probe_mask})
    EXPECT_TRUE(torch::equal(a.*m, b.*m));
  pm::ModelConfig bad = input;
  bad.target_units = "relative";
  try {
    pm::target_radiance(bad);
    ADD_FAILURE() << "an unknown unit was accepted";
  } catch (const phyir::Error& e) {
    EXPECT_NE(std::string(e.what()).find("'relative'"), std::string::npos) << e.what();
  }
}

TEST_F(ExposureOnDataset, RenderingLayerReproducesTheLinearInputInInputUnits) {
  const pm::ModelConfig c = native(view_);
  const double stops = stops_of(view_);
  std::printf("[Exposure] %s: exposure %+.3f stops\n", view_.string().c_str(), stops);
  ASSERT_GT(std::abs(stops), 0.5) << "the check below cannot tell the units apart at this exposure";
  const int H = c.render_height, W = c.render_width;
  // input.png's linear values at the grid, over pixels no input pixel of which clipped.
  const torch::Tensor input = pm::image_to_tensor(phyir::read_image(view_ / "input.png")).unsqueeze(0);
  const torch::Tensor linear = pm::resize(pm::srgb_decode(input), H, W);
  const torch::Tensor unclipped =
      (F::max_pool2d(std::get<0>(input.max(1, true)), F::MaxPool2dFuncOptions({input.size(2) / H, input.size(3) / W})) <
       0.99f).to(torch::kFloat);
  for (const phyir::view::RadianceUnits units : {phyir::view::RadianceUnits::kInput, phyir::view::RadianceUnits::kAbsolute}) {
    const pm::ViewTensors v = pm::load_view(view_, c, units);
    auto lo = [&](const torch::Tensor& x) { return pm::resize(x.unsqueeze(0), H, W); };
    pm::RenderSettings rs;
    rs.diffuse_samples = 512;
    rs.specular_samples = 256;
    torch::manual_seed(1);
    const torch::Tensor image =
        pm::render_layer(F::normalize(lo(v.normal), F::NormalizeFuncOptions().dim(1).eps(1e-6)), lo(v.base_color),
                         lo(v.roughness), lo(v.metalness), v.probes.unsqueeze(0), rs).image;
    const torch::Tensor mask = (v.render_mask * v.probe_mask).unsqueeze(0) * unclipped;
    const double n = mask.sum().item<double>();
    ASSERT_GT(n, 0.25 * H * W);
    const double rel_mse = ((image - linear).square() * mask).sum().item<double>() /
                           (linear.square() * mask).sum().item<double>();
    const double ratio = (image * mask).sum().item<double>() / (linear * mask).sum().item<double>();
    std::printf("[Exposure] %s units: %g pixels, relative MSE %.4f, mean re-render / mean linear input %.4f\n",
                units == phyir::view::RadianceUnits::kInput ? "input" : "absolute", n, rel_mse, ratio);
    if (units == phyir::view::RadianceUnits::kInput) {
      EXPECT_LT(rel_mse, 0.15);
      EXPECT_NEAR(ratio, 1.0, 0.2);
    } else {
      EXPECT_NEAR(ratio, std::exp2(-stops), 0.2 * std::exp2(-stops));  // off by the exposure factor
    }
  }
}
