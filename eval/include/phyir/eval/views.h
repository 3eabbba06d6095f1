#pragma once
// What one evaluated view holds: the ground truth (a view folder of `phyir dataset`,
// docs/dataset.md) and a method's prediction (the files `phyir infer` writes,
// docs/commands/infer.md; layout in docs/eval.md).
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "phyir/core/image.h"
#include "phyir/eval/probe_set.h"
#include "phyir/view/view_files.h"
#include "phyir/view/view_record.h"

namespace phyir::eval {

struct GroundTruthView {
  std::string id;      // room_0/v003
  std::string scene;   // room_0
  std::filesystem::path dir;
  float exposure_stops = 0.0f;  // input.png's exposure (for tone-mapping previews alike)
  Image color, input, depth, normal, basecolor, roughness, metalness;
  Image valid;         // mask_geometry and not mask_emissive and not mask_transparent
  std::optional<view::ProbeMosaic> probes;
};

// Reads the view of `record` (view/view_record.h). Missing or malformed files: phyir::Error
// naming the file.
GroundTruthView load_ground_truth(const view::ViewRecord& record);

// A prediction; any map may be absent (baselines predict only some). Predictions read from a
// folder must have the five maps (load_prediction checks); probes and the re-render are optional.
struct Prediction {
  std::optional<Image> depth, normal, basecolor, roughness, metalness, rerender;
  std::optional<view::ProbeMosaic> probes;
  std::vector<std::string> missing;  // optional files that were absent (for the report)
};

// Reads PRED/<view id>/ (depth.exr, normal.exr, basecolor.exr, roughness.exr, metalness.exr
// required, all of one size; rerender.exr, probes.exr + probe_mask.exr optional).
Prediction load_prediction(const std::filesystem::path& dir);


}  // namespace phyir::eval
