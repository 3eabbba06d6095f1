#include "phyir/eval/depth_protocol.h"

#include "phyir/core/error.h"
#include "phyir/core/image_resample.h"
#include "phyir/eval/unifuse_depth.h"

namespace phyir::eval {

const std::vector<std::string>& depth_protocol_names() {
  static const std::vector<std::string> names = {"toolkit", "unifuse", "unifuse-median"};
  return names;
}

const std::string& depth_protocol_name(DepthProtocol protocol) {
  return depth_protocol_names().at(size_t(protocol));
}

DepthProtocol parse_depth_protocol(const std::string& name) {
  const auto& names = depth_protocol_names();
  for (size_t k = 0; k < names.size(); ++k)
    if (names[k] == name) return DepthProtocol(k);
  fail("depth protocol '{}' is none of toolkit (the default), unifuse, unifuse-median", name);
}

std::string depth_protocol_description(DepthProtocol protocol) {
  if (protocol == DepthProtocol::kToolkit)
    return "Depth protocol `toolkit` (the default): Euclidean depth in metres at the coarser of the two "
           "resolutions, the maps' mask and ground truth > 0, predictions raised to 1 mm, no upper cap, "
           "no median scaling; RMSElog in natural log.";
  return "Depth protocol `" + depth_protocol_name(protocol) +
         "`: UniFuse's evaluation exactly: the ground truth resized onto the prediction's resolution by "
         "nearest neighbour (cv2 INTER_NEAREST), pixels with ground truth in (0, 10] m (no light or glass "
         "mask), ground truth and prediction raised to 0.1 m, ground truth set to 10 m where the prediction "
         "exceeds 10 m" +
         (protocol == DepthProtocol::kUnifuseMedian ? ", the prediction scaled by median(gt) / median(pred)"
                                                    : ", no median scaling") +
         "; RMSElog in log10. Per-view values averaged over views (UniFuse's evaluate.py: one image per "
         "Evaluator call).";
}

DepthMetrics view_depth_metrics(DepthProtocol protocol, const Image& pred, const Image& gt_depth,
                                const Image& gt_valid) {
  if (protocol == DepthProtocol::kToolkit) {
    const Size size = coarser({gt_valid.width, gt_valid.height}, {pred.width, pred.height});
    return depth_metrics(at_size(pred, size), at_size(gt_depth, size), mask_resize(gt_valid, size.width, size.height));
  }
  const Image gt = nearest_resize(gt_depth, pred.width, pred.height);
  return unifuse_depth_metrics(pred, gt, protocol == DepthProtocol::kUnifuseMedian);
}

}  // namespace phyir::eval
