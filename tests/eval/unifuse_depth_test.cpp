// The depth protocols of phyir eval: `unifuse` and `unifuse-median` against an independent
// NumPy implementation of UniFuse's evaluation (tests/eval/unifuse_depth_reference.py,
// Debian's /usr/bin/python3), to 1e-6 relative, on several views of random depths that cross
// every clamp; `toolkit` stays the default and gives the numbers it gave before.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <unistd.h>

#include <nlohmann/json.hpp>

#include "phyir/core/error.h"
#include "phyir/core/pcg32.h"
#include "phyir/eval/depth_protocol.h"
#include "phyir/eval/evaluate_view.h"
#include "phyir/core/image_resample.h"
#include "phyir/eval/suite.h"
#include "phyir/eval/unifuse_depth.h"

namespace phyir::eval {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

const char* const kDepthKeys[] = {"mae", "abs_rel", "sq_rel", "rmse", "rmse_log", "log10", "delta1", "delta2", "delta3"};

// Depths over [lo, hi] with a share of exact zeros (no surface).
Image random_depth(int w, int h, float lo, float hi, uint64_t seed) {
  Pcg32 rng(seed, 5);
  Image im(w, h, 1);
  for (float& v : im.pixels) v = rng.chance(0.08f) ? 0.0f : rng.uniform(lo, hi);
  return im;
}

json rows(const Image& im) {
  json out = json::array();
  for (int y = 0; y < im.height; ++y) {
    json row = json::array();
    for (int x = 0; x < im.width; ++x) row.push_back(double(im.at(x, y)));  // NaN -> null
    out.push_back(row);
  }
  return out;
}

// A view holding only what the depth metrics read: its depth, and a light/glass mask
// (`valid`) that the toolkit protocol applies and UniFuse's does not.
GroundTruthView depth_view(const Image& depth, uint64_t seed) {
  GroundTruthView v;
  v.id = "room_0/v" + std::to_string(seed);
  v.scene = "room_0";
  v.depth = depth;
  v.color = Image(depth.width, depth.height, 3, 0.5f);
  v.valid = Image(depth.width, depth.height, 1, 1.0f);
  Pcg32 rng(seed, 9);
  for (float& m : v.valid.pixels) m = rng.chance(0.1f) ? 0.0f : 1.0f;
  return v;
}

struct DepthCase {
  GroundTruthView gt;
  Prediction pred;
};

// Four views: prediction at the ground truth's size, finer (2x), coarser by a non-integer
// ratio, and finer by one; ground truth in [0.02, 12.5] m (below 0.1, above 10, zeros, one
// NaN), predictions in [-0.3, 13] m (negative, below 0.1, above 10).
std::vector<DepthCase> depth_cases() {
  struct Shape {
    int gw, gh, pw, ph;
  };
  const Shape shapes[] = {{24, 12, 24, 12}, {16, 8, 32, 16}, {23, 11, 16, 8}, {20, 10, 21, 11}};
  std::vector<DepthCase> cases;
  uint64_t seed = 100;
  for (const Shape& s : shapes) {
    DepthCase c{depth_view(random_depth(s.gw, s.gh, 0.02f, 12.5f, seed), seed), {}};
    c.pred.depth = random_depth(s.pw, s.ph, -0.3f, 13.0f, seed + 1);
    for (float& p : c.pred.depth->pixels)
      if (p == 0.0f) p = 0.05f;  // zeros belong to the ground truth
    cases.push_back(std::move(c));
    seed += 2;
  }
  cases[0].gt.depth.at(5, 3) = std::nanf("");
  return cases;
}

EvalSettings depth_only(DepthProtocol protocol) {
  EvalSettings s;
  s.relight = false;
  s.depth_protocol = protocol;
  return s;
}

json run_reference(const json& cases) {
  const fs::path dir = fs::temp_directory_path() / ("phyir_unifuse_depth_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  std::ofstream(dir / "cases.json") << json{{"cases", cases}}.dump();
  const std::string script = std::string(PHYIR_SOURCE_ROOT) + "/tests/eval/unifuse_depth_reference.py";
  const std::string cmd = "/usr/bin/python3 '" + script + "' '" + (dir / "cases.json").string() + "' '" +
                          (dir / "results.json").string() + "'";
  const int status = std::system(cmd.c_str());
  EXPECT_EQ(status, 0) << cmd << " failed: needs /usr/bin/python3 with python3-numpy (scripts/install_deps.sh)";
  json results;
  std::ifstream(dir / "results.json") >> results;
  fs::remove_all(dir);
  return results;
}

void expect_relative(double ours, const json& reference, const std::string& what) {
  ASSERT_TRUE(reference.is_number()) << what << ": reference is " << reference.dump();
  const double r = reference.get<double>();
  EXPECT_NEAR(ours, r, 1e-6 * std::abs(r) + 1e-15) << what;
}

TEST(UnifuseDepth, MatchesNumpyReferenceOverSeveralViews) {
  const std::vector<DepthCase> views = depth_cases();
  json cases = json::array();
  for (const auto& [name, median] : {std::pair{"plain", false}, std::pair{"median", true}}) {
    json v = json::array();
    for (const DepthCase& c : views) v.push_back({{"pred", rows(*c.pred.depth)}, {"gt", rows(c.gt.depth)}});
    cases.push_back({{"name", name}, {"median_align", median}, {"views", v}});
  }
  const json ref = run_reference(cases);
  ASSERT_TRUE(ref.contains("plain") && ref.contains("median"));
  // The inputs cross every clamp of the protocol.
  EXPECT_GT(ref["plain"]["clamped"]["gt_low"].get<int>(), 0);
  EXPECT_GT(ref["plain"]["clamped"]["pred_low"].get<int>(), 0);
  EXPECT_GT(ref["plain"]["clamped"]["pred_high"].get<int>(), 0);
  for (const auto& [name, protocol] : {std::pair{"plain", DepthProtocol::kUnifuse},
                                       std::pair{"median", DepthProtocol::kUnifuseMedian}}) {
    std::vector<Metrics> per_view;
    for (size_t k = 0; k < views.size(); ++k) {
      per_view.push_back(evaluate_view(views[k].gt, views[k].pred, depth_only(protocol)));
      const json& r = ref[name]["per_view"][k];
      EXPECT_EQ(per_view.back().at("pixels_depth"), r["pixels"].get<double>()) << name << " view " << k;
      for (const char* key : kDepthKeys)
        expect_relative(per_view.back().at(std::string("depth_") + key), r[key],
                        std::string(name) + " view " + std::to_string(k) + " " + key);
    }
    // UniFuse's averaging: its Evaluator sees one image at a time, so the mean over views.
    const Metrics mean = mean_metrics(per_view);
    for (const char* key : kDepthKeys)
      expect_relative(mean.at(std::string("depth_") + key), ref[name]["mean"][key], std::string(name) + " mean " + key);
  }
}

TEST(UnifuseDepth, AViewWithNothingCountedIsUndefinedOnBothSides) {
  Image gt(6, 4, 1, 11.0f);  // every pixel beyond UniFuse's 10 m
  gt.at(0, 0) = 0.0f;
  gt.at(1, 0) = std::nanf("");
  const Image pred(6, 4, 1, 3.0f);
  json view = {{"pred", rows(pred)}, {"gt", rows(gt)}};
  json empty = {{"name", "empty"}, {"median_align", false}, {"views", json::array()}};
  empty["views"].push_back(view);
  const json ref = run_reference(json::array({empty}));
  EXPECT_TRUE(ref["empty"]["per_view"][0].is_null());
  const DepthMetrics d = unifuse_depth_metrics(pred, gt, false);
  EXPECT_EQ(d.pixels, 0);
  EXPECT_TRUE(std::isnan(d.abs_rel) && std::isnan(d.delta1) && std::isnan(d.rmse_log));
}

TEST(UnifuseDepth, ClampsFollowUnifuse) {
  // One pixel per rule: gt below 0.1 is raised; pred below 0.1 is raised; pred above 10 sets
  // gt to 10 and keeps its own value.
  Image gt(3, 1, 1), pred(3, 1, 1);
  gt.at(0, 0) = 0.05f, pred.at(0, 0) = 0.2f;   // |0.1 - 0.2|
  gt.at(1, 0) = 2.0f, pred.at(1, 0) = -1.0f;   // |2 - 0.1|
  gt.at(2, 0) = 4.0f, pred.at(2, 0) = 12.0f;   // |10 - 12|
  const DepthMetrics d = unifuse_depth_metrics(pred, gt, false);
  const double g0 = kUnifuseMinDepth, p0 = 0.2f, p1 = kUnifuseMinDepth;
  EXPECT_NEAR(d.mae, ((p0 - g0) + (2.0 - p1) + 2.0) / 3.0, 1e-12);
  EXPECT_NEAR(d.abs_rel, ((p0 - g0) / g0 + (2.0 - p1) / 2.0 + 2.0 / 10.0) / 3.0, 1e-12);
  EXPECT_NEAR(d.delta1, 1.0 / 3.0, 1e-12);  // only 10 vs 12 is within 1.25
}

TEST(UnifuseDepth, NearestResizeFollowsOpenCv) {
  // cv2.resize(INTER_NEAREST) reads source floor(i * in / out): not pixel-centre aligned.
  Image row(5, 1, 1);
  for (int x = 0; x < 5; ++x) row.at(x, 0) = float(x);
  const Image down = nearest_resize(row, 2, 1), up = nearest_resize(row, 8, 1);
  EXPECT_EQ(down.at(0, 0), 0.0f);
  EXPECT_EQ(down.at(1, 0), 2.0f);
  const float want[] = {0, 0, 1, 1, 2, 3, 3, 4};  // floor(i * 0.625)
  for (int x = 0; x < 8; ++x) EXPECT_EQ(up.at(x, 0), want[x]) << x;
}

TEST(DepthProtocol, ToolkitIsTheDefaultAndUnchanged) {
  EXPECT_EQ(EvalSettings{}.depth_protocol, DepthProtocol::kToolkit);
  const std::vector<DepthCase> views = depth_cases();
  for (const DepthCase& c : views) {
    // The toolkit's rule as evaluate_view applied it before protocols existed.
    const Size size = coarser({c.gt.color.width, c.gt.color.height}, {c.pred.depth->width, c.pred.depth->height});
    const DepthMetrics before = depth_metrics(at_size(*c.pred.depth, size), at_size(c.gt.depth, size),
                                              mask_resize(c.gt.valid, size.width, size.height));
    EvalSettings defaults;
    defaults.relight = false;
    const Metrics m = evaluate_view(c.gt, c.pred, defaults);
    EXPECT_EQ(m.at("depth_abs_rel"), before.abs_rel);
    EXPECT_EQ(m.at("depth_rmse_log"), before.rmse_log);
    EXPECT_EQ(m.at("depth_delta1"), before.delta1);
    EXPECT_EQ(m.at("pixels_depth"), double(before.pixels));
  }
}

TEST(DepthProtocol, TheFlagIsHonoured) {
  // Depths inside [0.1, 10] at one size and every pixel valid: the protocols count the same
  // pixels and differ only in RMSE log's base (ln vs log10).
  GroundTruthView v = depth_view(random_depth(16, 8, 0.5f, 6.0f, 7), 7);
  v.valid = Image(16, 8, 1, 1.0f);
  Prediction p;
  p.depth = random_depth(16, 8, 0.5f, 6.0f, 8);
  for (float& x : p.depth->pixels)
    if (x == 0.0f) x = 1.0f;
  const Metrics toolkit = evaluate_view(v, p, depth_only(DepthProtocol::kToolkit));
  const Metrics unifuse = evaluate_view(v, p, depth_only(DepthProtocol::kUnifuse));
  EXPECT_EQ(toolkit.at("pixels_depth"), unifuse.at("pixels_depth"));
  EXPECT_NEAR(toolkit.at("depth_abs_rel"), unifuse.at("depth_abs_rel"), 1e-12);
  EXPECT_NEAR(toolkit.at("depth_log10"), unifuse.at("depth_log10"), 1e-12);
  EXPECT_NEAR(toolkit.at("depth_rmse_log"), unifuse.at("depth_rmse_log") * std::log(10.0), 1e-9);
  EXPECT_GT(std::abs(toolkit.at("depth_rmse_log") - unifuse.at("depth_rmse_log")), 1e-3);
  // The light/glass mask counts under toolkit only.
  v.valid.at(2, 2) = 0.0f;
  EXPECT_EQ(evaluate_view(v, p, depth_only(DepthProtocol::kToolkit)).at("pixels_depth"),
            unifuse.at("pixels_depth") - 1);
  EXPECT_EQ(evaluate_view(v, p, depth_only(DepthProtocol::kUnifuse)).at("pixels_depth"), unifuse.at("pixels_depth"));
}

TEST(DepthProtocol, NamesParseAndBadNamesAreNamed) {
  for (const std::string& name : depth_protocol_names())
    EXPECT_EQ(depth_protocol_name(parse_depth_protocol(name)), name);
  EXPECT_EQ(parse_depth_protocol("unifuse"), DepthProtocol::kUnifuse);
  try {
    parse_depth_protocol("UniFuse");
    ADD_FAILURE() << "no error for an unknown protocol";
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("'UniFuse'"), std::string::npos) << message;
    EXPECT_NE(message.find("toolkit"), std::string::npos) << message;
    EXPECT_NE(message.find("unifuse-median"), std::string::npos) << message;
  }
}

}  // namespace
}  // namespace phyir::eval
