#pragma once
// The side-by-side PNG of one view: columns input / ground truth / prediction, one row per
// map, relit spheres last (layout described in report.md). HDR images are tone-mapped through
// OpenColorIO (core/colour.h) at the view's input exposure, so they look like input.png.
#include <filesystem>

#include "phyir/eval/evaluate_view.h"
#include "phyir/eval/views.h"

namespace phyir::eval {

void write_side_by_side(const std::filesystem::path& file, const GroundTruthView& gt, const ViewImages& pred);

}  // namespace phyir::eval
