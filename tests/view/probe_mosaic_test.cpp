// probes.exr + probe_mask.exr: layout, reading, writing, resampling between layouts.
#include <gtest/gtest.h>

#include <filesystem>

#include "phyir/core/error.h"
#include "phyir/core/image_io.h"
#include "phyir/core/setting_error.h"
#include "phyir/view/probe_mosaic.h"
#include "phyir/view/view_files.h"

namespace fs = std::filesystem;
namespace pv = phyir::view;

namespace {

// A mosaic whose texel value says which probe and texel it is: 1000 i + 100 j + 10 r + c.
pv::ProbeMosaic numbered(const pv::ProbeLayout& layout) {
  pv::ProbeMosaic m;
  m.layout = layout;
  m.radiance = phyir::Image(layout.mosaic_width(), layout.mosaic_height(), 3);
  for (int y = 0; y < layout.mosaic_height(); ++y)
    for (int x = 0; x < layout.mosaic_width(); ++x)
      for (int k = 0; k < 3; ++k) {
        const int i = y / layout.res_height, j = x / layout.res_width, r = y % layout.res_height, c = x % layout.res_width;
        m.radiance.at(x, y, k) = float(1000 * i + 100 * j + 10 * r + c + k);
      }
  m.mask = phyir::Image(layout.grid_width, layout.grid_height, 1, 1.0f);
  m.mask.at(1, 0, 0) = 0.0f;
  return m;
}

fs::path scratch(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("phyir_probe_mosaic_test_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

}  // namespace

TEST(ProbeLayout, MosaicPixelsAndValidation) {
  const pv::ProbeLayout layout{2, 4, 3, 5};
  EXPECT_EQ(layout.mosaic_width(), 20);
  EXPECT_EQ(layout.mosaic_height(), 6);
  // Probe 5 = (1, 1), texel 7 = (1, 2): column 1*5 + 2, row 1*3 + 1.
  EXPECT_EQ(layout.mosaic_pixel(5, 7), glm::ivec2(7, 4));
  EXPECT_NO_THROW(layout.validate());
  try {
    pv::ProbeLayout{0, 4, 3, 5}.validate();
    FAIL();
  } catch (const phyir::SettingError& e) {
    EXPECT_EQ(e.setting(), "probe.grid");
  }
  try {
    pv::ProbeLayout{2, 4, 3, 5000}.validate();
    FAIL();
  } catch (const phyir::SettingError& e) {
    EXPECT_EQ(e.setting(), "probe.res");
  }
  int h = 0, w = 0;
  pv::parse_size("16x32", "probe.res", &h, &w);
  EXPECT_EQ(h, 16);
  EXPECT_EQ(w, 32);
  EXPECT_THROW(pv::parse_size("16by32", "probe.res", &h, &w), phyir::SettingError);
}

TEST(ProbeMosaic, ProbeReadsItsBlock) {
  const pv::ProbeMosaic m = numbered({2, 4, 3, 5});
  const phyir::Image p = m.probe(1, 2);
  EXPECT_EQ(p.width, 5);
  EXPECT_EQ(p.height, 3);
  EXPECT_EQ(p.at(4, 2, 0), 1000.0f + 200.0f + 20.0f + 4.0f);
  EXPECT_FALSE(m.valid(0, 1));
  EXPECT_TRUE(m.valid(1, 1));
  EXPECT_EQ(m.scaled(2.0).probe(1, 2).at(4, 2, 0), 2.0f * 1224.0f);
}

TEST(ProbeMosaic, WriteThenReadIsExact) {
  const fs::path dir = scratch("round_trip");
  const pv::ProbeMosaic m = numbered({2, 4, 3, 5});
  pv::write_probe_mosaic(dir, m);
  ASSERT_TRUE(pv::has_probes(dir));
  const pv::ProbeMosaic back = pv::read_probe_mosaic(dir);
  EXPECT_EQ(back.layout, m.layout);
  EXPECT_EQ(back.radiance.pixels, m.radiance.pixels);
  EXPECT_EQ(back.mask.pixels, m.mask.pixels);
}

TEST(ProbeMosaic, MismatchedFilesAreNamed) {
  const fs::path dir = scratch("mismatch");
  const pv::ProbeMosaic m = numbered({2, 4, 3, 5});
  phyir::write_image(dir / pv::kProbesFile, m.radiance);
  EXPECT_THROW(pv::has_probes(dir), phyir::Error);  // probes.exr without probe_mask.exr
  phyir::write_image(dir / pv::kProbeMaskFile, phyir::Image(3, 2, 1, 1.0f));  // 20 is not a multiple of 3
  try {
    pv::read_probe_mosaic(dir);
    FAIL();
  } catch (const phyir::Error& e) {
    EXPECT_NE(std::string(e.what()).find(pv::kProbesFile), std::string::npos) << e.what();
  }
}

TEST(ProbeMosaic, ResampledTakesTheNearestProbeAndAveragesTexels) {
  pv::ProbeMosaic m = numbered({2, 4, 4, 6});
  m.mask.at(3, 1, 0) = 0.0f;  // source probe (1, 3) invalid
  EXPECT_EQ(m.resampled(m.layout).radiance.pixels, m.radiance.pixels);
  // A 1x2 grid of 2x3 texels: target probe (0, j) is the source probe whose cell holds its
  // cell's centre, (1, 1) and (1, 3); each target texel the mean of a 2x2 block of texels.
  const pv::ProbeMosaic r = m.resampled({1, 2, 2, 3});
  const float block_mean = (0.0f + 1.0f + 10.0f + 11.0f) / 4.0f;  // texels (0..1, 0..1)
  EXPECT_FLOAT_EQ(r.probe(0, 0).at(0, 0, 0), 1100.0f + block_mean);
  EXPECT_FLOAT_EQ(r.probe(0, 1).at(0, 0, 0), 1300.0f + block_mean);
  EXPECT_TRUE(r.valid(0, 0));
  EXPECT_FALSE(r.valid(0, 1));
}
