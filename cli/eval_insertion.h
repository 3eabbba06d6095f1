#pragma once
// `phyir eval --insertion-views N`: the insertion benchmark (insert/insert_bench.h) on the first
// N views of the evaluated split, with the method's predicted probes beside the GT probes, the
// global probe and the constant environment, as a section of eval's report (docs/eval.md
// "Object insertion"). It lives in the cli because it needs both eval and insert, and insert
// already builds on eval.
#include <filesystem>
#include <string>

#include "phyir/eval/suite.h"

namespace phyir::cli {

struct EvalInsertionOptions {
  std::filesystem::path gt_dir, pred_dir, out_dir;  // out_dir/insertion/ holds the composites
  std::string split;
  int views = 0;                  // the first N views of the split
  std::filesystem::path scenes;   // the scenes folder, when the manifest's scenes_dir is not reachable
  int spp = 64, truth_spp = 256, seeds = 1;
  float sphere_radius = 0.15f;
  bool progress = true;
};

// The insertion scores as a report section (key "insertion"): per view and placement, each
// Table 10 sphere composited under each lighting and scored against the truth, and the means
// per material. Errors (phyir::Error) name the view and the file: a scene that cannot be found
// or whose checksum is not the manifest's, a prediction folder without probes.
eval::ReportSection evaluate_insertion(const EvalInsertionOptions& options);

}  // namespace phyir::cli
