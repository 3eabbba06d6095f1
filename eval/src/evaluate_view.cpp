#include "phyir/eval/evaluate_view.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "phyir/core/error.h"
#include "phyir/eval/pixel_metrics.h"
#include "phyir/view/radiance_units.h"
#include "phyir/core/image_resample.h"

namespace phyir::eval {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

Image normalised(Image n) {
  for (int y = 0; y < n.height; ++y)
    for (int x = 0; x < n.width; ++x) {
      double s = 0.0;
      for (int c = 0; c < 3; ++c) s += double(n.at(x, y, c)) * n.at(x, y, c);
      if (s > 1e-20)
        for (int c = 0; c < 3; ++c) n.at(x, y, c) = float(n.at(x, y, c) / std::sqrt(s));
    }
  return n;
}

}  // namespace

const std::vector<std::string>& metric_names() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> n = {"basecolor_mse", "normal_deg", "roughness_mse", "metalness_mse", "rerender_mse",
                                  "depth_mae", "depth_abs_rel", "depth_sq_rel", "depth_rmse", "depth_rmse_log",
                                  "depth_log10", "depth_delta1", "depth_delta2", "depth_delta3", "probe_ssim"};
    for (const SphereMaterial& m : sphere_materials()) {
      n.push_back("relight_" + m.key + "_mae");
      n.push_back("relight_" + m.key + "_rmse");
    }
    for (const char* c : {"pixels_maps", "pixels_depth", "pixels_rerender", "probes_compared", "relight_positions"})
      n.push_back(c);
    return n;
  }();
  return names;
}

bool higher_is_better(const std::string& metric) {
  return metric == "probe_ssim" || metric.rfind("depth_delta", 0) == 0;
}

std::vector<std::pair<int, int>> relight_positions(const Image& valid, int count) {
  std::vector<std::pair<int, int>> cells, chosen;
  for (int i = 0; i < valid.height; ++i)
    for (int j = 0; j < valid.width; ++j)
      if (valid.at(j, i, 0) > 0.5f) cells.emplace_back(i, j);
  if (cells.empty() || count <= 0) return chosen;
  const int n = std::min<int>(count, static_cast<int>(cells.size()));
  for (int k = 0; k < n; ++k) chosen.push_back(cells[size_t((k + 0.5) * cells.size() / n)]);
  return chosen;
}

namespace {

// Maps and depth, at the coarser of the two resolutions.
void score_maps(const GroundTruthView& gt, const Prediction& pred, const EvalSettings& settings, Metrics* out) {
  Metrics& m = *out;
  const Image* any_map = pred.depth ? &*pred.depth : pred.basecolor ? &*pred.basecolor : pred.normal ? &*pred.normal
                         : pred.roughness ? &*pred.roughness : pred.metalness ? &*pred.metalness : nullptr;
  if (!any_map) return;
  const Size size = coarser({gt.color.width, gt.color.height}, {any_map->width, any_map->height});
  const Image mask = mask_resize(gt.valid, size.width, size.height);
  m["pixels_maps"] = double(count_mask(mask));
  if (pred.basecolor) m["basecolor_mse"] = masked_mse(at_size(*pred.basecolor, size), at_size(gt.basecolor, size), mask);
  if (pred.roughness) m["roughness_mse"] = masked_mse(at_size(*pred.roughness, size), at_size(gt.roughness, size), mask);
  if (pred.metalness) m["metalness_mse"] = masked_mse(at_size(*pred.metalness, size), at_size(gt.metalness, size), mask);
  if (pred.normal)
    m["normal_deg"] = mean_angular_error_deg(normalised(at_size(*pred.normal, size)), normalised(at_size(gt.normal, size)),
                                             mask);
  if (pred.depth) {
    const DepthMetrics d = view_depth_metrics(settings.depth_protocol, *pred.depth, gt.depth, gt.valid);
    m["pixels_depth"] = double(d.pixels);
    m["depth_mae"] = d.mae, m["depth_abs_rel"] = d.abs_rel, m["depth_sq_rel"] = d.sq_rel;
    m["depth_rmse"] = d.rmse, m["depth_rmse_log"] = d.rmse_log, m["depth_log10"] = d.log10;
    m["depth_delta1"] = d.delta1, m["depth_delta2"] = d.delta2, m["depth_delta3"] = d.delta3;
  }
}

// Table 5: every sphere material relit by the predicted and the true probe at the same
// positions (probes already in the scoring unit). The first position's spheres go to the
// figure divided by `scale`, back in color.exr's unit as the figure shows it.
void score_relighting(const view::ProbeMosaic& pred, const view::ProbeMosaic& gt, const ProbeScore& score, const EvalSettings& settings,
                      double scale, Metrics* out, ViewImages* images) {
  // Positions on the compared grid where both sides are valid.
  Image both(score.grid_w, score.grid_h, 1);
  auto cells = [&](int i, int j, int* pi, int* pj, int* gi, int* gj) {
    view::nearest_cell(i, j, score.grid_h, score.grid_w, pred.layout.grid_height, pred.layout.grid_width, pi, pj);
    view::nearest_cell(i, j, score.grid_h, score.grid_w, gt.layout.grid_height, gt.layout.grid_width, gi, gj);
  };
  for (int i = 0; i < score.grid_h; ++i)
    for (int j = 0; j < score.grid_w; ++j) {
      int pi, pj, gi, gj;
      cells(i, j, &pi, &pj, &gi, &gj);
      both.at(j, i) = pred.valid(pi, pj) && gt.valid(gi, gj) ? 1.0f : 0.0f;
    }
  const auto positions = relight_positions(both, settings.relight_positions);
  (*out)["relight_positions"] = double(positions.size());
  const auto& materials = sphere_materials();
  for (size_t k = 0; k < materials.size(); ++k) {
    double abs = 0.0, sq = 0.0;
    long n = 0;
    for (size_t p = 0; p < positions.size(); ++p) {
      int pi, pj, gi, gj;
      cells(positions[p].first, positions[p].second, &pi, &pj, &gi, &gj);
      // Each side lit by its own probe at its own texel resolution; same seed for both.
      RelitSphere a = relight_sphere(pred.probe(pi, pj), materials[k], settings.sphere);
      RelitSphere b = relight_sphere(gt.probe(gi, gj), materials[k], settings.sphere);
      const double pixels = double(count_mask(b.mask)) * 3.0;
      abs += masked_mae(a.color, b.color, b.mask) * pixels;
      sq += masked_mse(a.color, b.color, b.mask) * pixels;
      n += long(pixels);
      if (images && p == 0) {
        for (RelitSphere* sphere : {&a, &b})
          for (float& v : sphere->color.pixels) v = float(double(v) / scale);
        images->spheres_pred.push_back(std::move(a));
        images->spheres_gt.push_back(std::move(b));
      }
    }
    if (n > 0) {
      (*out)["relight_" + materials[k].key + "_mae"] = abs / n;
      (*out)["relight_" + materials[k].key + "_rmse"] = std::sqrt(sq / n);
    }
  }
}

}  // namespace

Metrics evaluate_view(const GroundTruthView& gt, const Prediction& pred, const EvalSettings& settings,
                      ViewImages* images) {
  Metrics m;
  for (const std::string& name : metric_names()) m[name] = kNaN;
  const Size gt_size{gt.color.width, gt.color.height};
  score_maps(gt, pred, settings, &m);
  // Radiance in the scoring unit: both sides times the same factor.
  const double scale = view::radiance_scale(settings.radiance_units, gt.exposure_stops);
  if (pred.rerender) {
    const Size size = coarser(gt_size, {pred.rerender->width, pred.rerender->height});
    const Image mask = mask_resize(gt.valid, size.width, size.height);
    m["pixels_rerender"] = double(count_mask(mask));
    m["rerender_mse"] = masked_mse(at_size(*pred.rerender, size), at_size(gt.color, size), mask) * scale * scale;
  }
  if (images) {
    auto show = [&](const std::optional<Image>& p) -> std::optional<Image> {
      if (!p) return std::nullopt;
      return area_resize(*p, gt_size.width, gt_size.height);
    };
    images->depth = show(pred.depth), images->normal = show(pred.normal), images->basecolor = show(pred.basecolor);
    images->roughness = show(pred.roughness), images->metalness = show(pred.metalness);
    images->rerender = show(pred.rerender);
  }
  // Probes (eq. 7) and relighting (Table 5).
  if (pred.probes && gt.probes) {
    // Copies only when the unit changes anything (absolute units: the probes as loaded).
    std::optional<view::ProbeMosaic> scaled_pred, scaled_gt;
    if (scale != 1.0) scaled_pred = pred.probes->scaled(scale), scaled_gt = gt.probes->scaled(scale);
    const view::ProbeMosaic& pred_probes = scaled_pred ? *scaled_pred : *pred.probes;
    const view::ProbeMosaic& gt_probes = scaled_gt ? *scaled_gt : *gt.probes;
    const ProbeScore score = probe_ssim(pred_probes, gt_probes);
    m["probe_ssim"] = score.ssim;
    m["probes_compared"] = double(score.probes);
    if (settings.relight) score_relighting(pred_probes, gt_probes, score, settings, scale, &m, images);
  }
  return m;
}

}  // namespace phyir::eval
