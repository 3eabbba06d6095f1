#pragma once
// One view's metrics for one method: every metric of the paper's Tables 2, 5, 6 and 7
// (names in metric_names()), each NaN when the method does not predict it or nothing counts.
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "phyir/eval/depth_protocol.h"
#include "phyir/view/radiance_units.h"
#include "phyir/eval/relight.h"
#include "phyir/eval/views.h"

namespace phyir::eval {

struct EvalSettings {
  bool relight = true;
  int relight_positions = 2;  // probe positions per view (spread over the valid probes)
  RelightSettings sphere;
  DepthProtocol depth_protocol = DepthProtocol::kToolkit;  // the rules of the depth_* metrics
  view::RadianceUnits radiance_units = view::RadianceUnits::kAbsolute;  // the unit of the radiance metrics
};

using Metrics = std::map<std::string, double>;

// Every metric key, in report order: basecolor_mse, normal_deg, roughness_mse,
// metalness_mse, rerender_mse, depth_{mae,abs_rel,sq_rel,rmse,rmse_log,log10,delta1,2,3},
// probe_ssim, relight_<material>_{mae,rmse}; and counts: pixels_maps, pixels_depth (under
// the depth protocol's mask), pixels_rerender, probes_compared, relight_positions.
const std::vector<std::string>& metric_names();
bool higher_is_better(const std::string& metric);  // SSIM and the deltas

// Images kept for the side-by-side figure (at the ground truth's resolution).
struct ViewImages {
  std::optional<Image> depth, normal, basecolor, roughness, metalness, rerender;
  std::vector<RelitSphere> spheres_pred, spheres_gt;  // first relighting position, per material
};

// Resolutions (docs/eval.md): maps at the coarser of the two (depth as its protocol says);
// the re-render against color.exr at the coarser of the two; probes as probe_set.h says.
Metrics evaluate_view(const GroundTruthView& gt, const Prediction& pred, const EvalSettings& settings,
                      ViewImages* images = nullptr);

// The probe positions the relighting uses on a grid_h x grid_w grid with validity `valid`:
// `count` cells spread evenly over the valid cells in row-major order.
std::vector<std::pair<int, int>> relight_positions(const Image& valid, int count);

}  // namespace phyir::eval
