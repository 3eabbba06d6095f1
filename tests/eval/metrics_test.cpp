// Every metric of phyir eval against an independent implementation: the test writes fixed
// inputs to JSON, scripts/eval_reference_metrics.py computes the same metrics with numpy,
// scipy and skimage (Debian's /usr/bin/python3), and the two must agree to 1e-6 relative
// (the C++ side sums in double from float inputs; the reference is double throughout).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <tuple>

#include <unistd.h>

#include <nlohmann/json.hpp>

#include "phyir/core/pcg32.h"
#include "phyir/eval/pixel_metrics.h"
#include "phyir/eval/probe_set.h"
#include "phyir/core/image_resample.h"
#include "phyir/eval/ssim.h"

namespace phyir::eval {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

Image random_image(int w, int h, int c, float lo, float hi, uint64_t seed) {
  Pcg32 rng(seed, 7);
  Image im(w, h, c);
  for (float& v : im.pixels) v = rng.uniform(lo, hi);
  return im;
}

// A mask with about 70% of the pixels counted.
Image random_mask(int w, int h, uint64_t seed) {
  Pcg32 rng(seed, 11);
  Image m(w, h, 1);
  for (float& v : m.pixels) v = rng.chance(0.7f) ? 1.0f : 0.0f;
  return m;
}

json to_json(const Image& im) {
  json rows = json::array();
  for (int y = 0; y < im.height; ++y) {
    json row = json::array();
    for (int x = 0; x < im.width; ++x) {
      json px = json::array();
      for (int c = 0; c < im.channels; ++c) px.push_back(double(im.at(x, y, c)));
      row.push_back(px);
    }
    rows.push_back(row);
  }
  return rows;
}

json mask_json(const Image& m) {
  json rows = json::array();
  for (int y = 0; y < m.height; ++y) {
    json row = json::array();
    for (int x = 0; x < m.width; ++x) row.push_back(double(m.at(x, y)));
    rows.push_back(row);
  }
  return rows;
}

class ReferenceMetrics : public ::testing::Test {
 protected:
  static json run(const json& cases) {
    const fs::path dir = fs::temp_directory_path() / ("phyir_eval_metrics_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    std::ofstream(dir / "cases.json") << json{{"cases", cases}}.dump();
    const std::string script = std::string(PHYIR_SOURCE_ROOT) + "/scripts/eval_reference_metrics.py";
    const std::string cmd = "/usr/bin/python3 '" + script + "' '" + (dir / "cases.json").string() + "' '" +
                            (dir / "results.json").string() + "'";
    const int status = std::system(cmd.c_str());
    EXPECT_EQ(status, 0) << cmd << " failed: needs /usr/bin/python3 with python3-numpy, python3-scipy and "
                         << "python3-skimage (scripts/install_deps.sh installs them)";
    json results;
    std::ifstream(dir / "results.json") >> results;
    fs::remove_all(dir);
    return results;
  }
};

void expect_close(double ours, double reference, const std::string& what, double rel = 1e-6) {
  EXPECT_NEAR(ours, reference, rel * std::max(1.0, std::abs(reference))) << what;
}

TEST_F(ReferenceMetrics, MseMaeAngularAndDepthMatchNumpy) {
  const int w = 23, h = 11;
  const Image mask = random_mask(w, h, 1);
  const Image bc_p = random_image(w, h, 3, 0, 1, 2), bc_g = random_image(w, h, 3, 0, 1, 3);
  const Image r_p = random_image(w, h, 1, 0, 1, 4), r_g = random_image(w, h, 1, 0, 1, 5);
  const Image n_p = random_image(w, h, 3, -1, 1, 6), n_g = random_image(w, h, 3, -1, 1, 7);
  Image d_p = random_image(w, h, 1, 0.3f, 6.0f, 8), d_g = random_image(w, h, 1, 0.3f, 6.0f, 9);
  // Edge cases: a non-positive prediction (clamped to 1 mm), a zero ground truth (left out),
  // a prediction close to the truth (inside delta1).
  d_p.at(0, 0) = -0.5f;
  d_g.at(1, 0) = 0.0f;
  d_p.at(2, 0) = d_g.at(2, 0) * 1.1f;
  json cases = json::array();
  cases.push_back({{"name", "mse3"}, {"metric", "mse"}, {"pred", to_json(bc_p)}, {"gt", to_json(bc_g)}, {"mask", mask_json(mask)}});
  cases.push_back({{"name", "mse1"}, {"metric", "mse"}, {"pred", to_json(r_p)}, {"gt", to_json(r_g)}, {"mask", mask_json(mask)}});
  cases.push_back({{"name", "mae3"}, {"metric", "mae"}, {"pred", to_json(bc_p)}, {"gt", to_json(bc_g)}, {"mask", mask_json(mask)}});
  cases.push_back({{"name", "angular"}, {"metric", "angular"}, {"pred", to_json(n_p)}, {"gt", to_json(n_g)}, {"mask", mask_json(mask)}});
  cases.push_back({{"name", "depth"}, {"metric", "depth"}, {"pred", to_json(d_p)}, {"gt", to_json(d_g)}, {"mask", mask_json(mask)}});
  const json ref = run(cases);
  ASSERT_FALSE(ref.is_null());
  expect_close(masked_mse(bc_p, bc_g, mask), ref["mse3"], "MSE, 3 channels");
  expect_close(masked_mse(r_p, r_g, mask), ref["mse1"], "MSE, 1 channel");
  expect_close(masked_mae(bc_p, bc_g, mask), ref["mae3"], "MAE");
  expect_close(mean_angular_error_deg(n_p, n_g, mask), ref["angular"], "mean angular error", 1e-5);
  const DepthMetrics d = depth_metrics(d_p, d_g, mask);
  const json& r = ref["depth"];
  expect_close(d.mae, r["mae"], "depth MAE");
  expect_close(d.abs_rel, r["abs_rel"], "AbsRel");
  expect_close(d.sq_rel, r["sq_rel"], "SqRel");
  expect_close(d.rmse, r["rmse"], "RMSE");
  expect_close(d.rmse_log, r["rmse_log"], "RMSE(log)");
  expect_close(d.log10, r["log10"], "log10");
  expect_close(d.delta1, r["delta1"], "delta1");
  expect_close(d.delta2, r["delta2"], "delta2");
  expect_close(d.delta3, r["delta3"], "delta3");
  // The inputs exercise every branch of the deltas (none of them is trivially 0 or 1).
  EXPECT_GT(d.delta1, 0.0);
  EXPECT_LT(d.delta3, 1.0);
}

TEST_F(ReferenceMetrics, SsimMatchesSkimageAndEq7MatchesScipy) {
  const int w = 32, h = 24;
  const Image x = random_image(w, h, 3, 0, 2, 21);
  Image y = x;
  Pcg32 rng(22, 1);
  for (float& v : y.pixels) v = 0.7f * v + rng.uniform(0.0f, 0.6f);  // correlated, not equal
  // skimage's Gaussian SSIM: an 11-tap window (truncate 3.5 at sigma 1.5), scipy "reflect"
  // padding, the mean over the image cropped by (win_size - 1) / 2.
  SsimOptions sk;
  sk.radius = 5;
  sk.rows = sk.columns = Padding::kReflect;
  json cases = json::array();
  for (int win : {5, 7, 11}) {
    cases.push_back({{"name", "skimage" + std::to_string(win)}, {"metric", "ssim_skimage"}, {"x", to_json(x)},
                     {"y", to_json(y)}, {"win_size", win}});
  }
  // Eq. 7's SSIM (the default options) on a small probe-like image, where the padding matters.
  const Image px = random_image(8, 4, 3, 0, 1.5f, 23), py = random_image(8, 4, 3, 0, 1.5f, 24);
  cases.push_back({{"name", "eq7_small"}, {"metric", "ssim_eq7"}, {"x", to_json(px)}, {"y", to_json(py)}});
  cases.push_back({{"name", "eq7_large"}, {"metric", "ssim_eq7"}, {"x", to_json(x)}, {"y", to_json(y)}});
  const json ref = run(cases);
  ASSERT_FALSE(ref.is_null());
  for (int win : {5, 7, 11}) {
    sk.crop = (win - 1) / 2;
    expect_close(ssim(x, y, sk), ref["skimage" + std::to_string(win)], "skimage win_size " + std::to_string(win));
  }
  expect_close(ssim(px, py), ref["eq7_small"], "eq. 7 SSIM, 8x4");
  expect_close(ssim(x, y), ref["eq7_large"], "eq. 7 SSIM, 32x24");
  EXPECT_NEAR(ssim(x, x), 1.0, 1e-12);
  // The padding is part of the definition: wrapping the columns changes the value.
  SsimOptions replicate;
  replicate.columns = Padding::kReplicate;
  EXPECT_GT(std::abs(ssim(px, py, replicate) - ssim(px, py)), 1e-4);
}

TEST_F(ReferenceMetrics, AreaResizeAndProbeSsimMatchNumpy) {
  const Image im = random_image(7, 5, 3, 0, 1, 31);
  // Ground-truth probes: a 4x8 grid of 4x8 texels; predicted: a 2x4 grid of 2x4 texels (both
  // coarser), so the comparison picks GT probes by cell centre and area-averages texels.
  view::ProbeMosaic gt, pred;
  gt.layout = {4, 8, 4, 8};
  gt.radiance = random_image(64, 16, 3, 0, 3, 32);
  gt.mask = random_mask(8, 4, 33);
  pred.layout = {2, 4, 2, 4};
  pred.radiance = random_image(16, 4, 3, 0, 3, 34);
  pred.mask = random_mask(4, 2, 35);
  pred.mask.at(0, 0) = 1.0f;  // at least one probe compared (its GT cell is (1, 1))
  gt.mask.at(1, 1) = 1.0f;
  json cases = json::array();
  cases.push_back({{"name", "down"}, {"metric", "area_resize"}, {"image", to_json(im)}, {"width", 3}, {"height", 2}});
  cases.push_back({{"name", "up"}, {"metric", "area_resize"}, {"image", to_json(im)}, {"width", 10}, {"height", 8}});
  cases.push_back({{"name", "probes"}, {"metric", "probe_ssim"}, {"pred", to_json(pred.radiance)}, {"gt", to_json(gt.radiance)},
                   {"pred_mask", mask_json(pred.mask)}, {"gt_mask", mask_json(gt.mask)}});
  const json ref = run(cases);
  ASSERT_FALSE(ref.is_null());
  for (const auto& [name, w, h] : {std::tuple{"down", 3, 2}, std::tuple{"up", 10, 8}}) {
    const Image r = area_resize(im, w, h);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        for (int c = 0; c < 3; ++c)
          EXPECT_NEAR(r.at(x, y, c), ref[name][y][x][c].get<double>(), 1e-6) << name << " " << x << "," << y;
  }
  const ProbeScore s = probe_ssim(pred, gt);
  EXPECT_EQ(s.grid_h, 2);
  EXPECT_EQ(s.h, 2);
  EXPECT_EQ(s.probes, ref["probes"]["probes"].get<long>());
  expect_close(s.ssim, ref["probes"]["ssim"], "probe SSIM", 1e-5);
}

}  // namespace
}  // namespace phyir::eval
