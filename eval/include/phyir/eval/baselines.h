#pragma once
// Baselines that give the numbers context (report rows):
//  - constant mean: every map is the mean of the ground truth over the valid pixels of the
//    reference views (the training split; the test split itself when there is no training
//    view, which the report says), normals the normalised mean normal, the re-render the mean
//    colour, every probe the per-texel mean of the reference views' valid probes (colour and
//    probes averaged in the unit the radiance metrics are scored in);
//  - input as base colour: input.png decoded to linear (OpenColorIO) taken as the base colour
//    (the "no intrinsic decomposition" answer); it predicts nothing else.
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "phyir/view/radiance_units.h"
#include "phyir/eval/views.h"

namespace phyir::eval {

struct BaselineStats {
  std::string source;          // e.g. "train split, 6 views"
  int views = 0;
  double basecolor[3] = {0, 0, 0}, roughness = 0, metalness = 0, depth = 0, color[3] = {0, 0, 0};
  double normal[3] = {0, 1, 0};  // normalised mean
  std::optional<Image> probe;    // per-texel mean probe (the reference's texel resolution)
  // The same means of colour and probes taken in each view's input units (radiance_units.h).
  double input_color[3] = {0, 0, 0};
  std::optional<Image> input_probe;
};

// Means over the views of `records`; `source` describes them.
BaselineStats compute_baseline_stats(const std::vector<view::ViewRecord>& records,
                                     const std::string& source);

// The constant re-render and probes are the means in `units` (absolute, or each view's input
// units, then returned in `gt`'s absolute unit for evaluate_view to score in input units).
Prediction constant_mean_prediction(const BaselineStats& stats, const GroundTruthView& gt,
                                    view::RadianceUnits units = view::RadianceUnits::kAbsolute);
Prediction input_as_basecolor_prediction(const GroundTruthView& gt);

}  // namespace phyir::eval
