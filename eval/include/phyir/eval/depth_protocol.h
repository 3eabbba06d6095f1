#pragma once
// Which rules score depth (`phyir eval`'s depth protocol, docs/eval.md "Depth protocols"):
//   toolkit         the default: the toolkit's masks and resolution rule, RMSE log in ln
//   unifuse         UniFuse's evaluate.py exactly (unifuse_depth.h): its mask, clamps, log10
//                   RMSE log, the ground truth resized onto the prediction as its loader does
//   unifuse-median  the same with UniFuse's median alignment (its median_align option)
// Every protocol averages per view over views, which is UniFuse's averaging: its evaluate.py
// feeds its Evaluator one image at a time (a "batch" of one view).
#include <string>
#include <vector>

#include "phyir/core/image.h"
#include "phyir/eval/pixel_metrics.h"

namespace phyir::eval {

enum class DepthProtocol { kToolkit, kUnifuse, kUnifuseMedian };

// The names, in the order of the enum ("toolkit", "unifuse", "unifuse-median").
const std::vector<std::string>& depth_protocol_names();
const std::string& depth_protocol_name(DepthProtocol protocol);
// phyir::Error naming the value and the choices when `name` is none of them.
DepthProtocol parse_depth_protocol(const std::string& name);

// What the protocol does, one paragraph for report.md.
std::string depth_protocol_description(DepthProtocol protocol);

// One view's depth metrics. toolkit: at the coarser of the two resolutions (area-resampled),
// pixels in the conservatively resampled `gt_valid` with gt > 0, prediction raised to 1 mm
// (depth_metrics). unifuse: at the prediction's resolution, `gt_depth` resized onto it by
// nearest_resize, UniFuse's val_mask on it and nothing else (`gt_valid` unused: 3D60 has no
// light or glass masks), unifuse_depth_metrics.
DepthMetrics view_depth_metrics(DepthProtocol protocol, const Image& pred, const Image& gt_depth,
                                const Image& gt_valid);

}  // namespace phyir::eval
