#pragma once
// The validation pass (docs/model.md "Validation"): the networks in eval mode on the first N
// views of the dataset's validation split, unaugmented, every few epochs. It reports the
// stage's loss and `phyir eval`'s metrics (the eval library's own definitions, on ground
// truth read as `phyir eval` reads it; relighting left out: it path-traces spheres). Torch's
// generator is saved, seeded for the pass and restored, so a pass changes nothing in training
// and its Monte-Carlo samples are the same every time. Private header (torch types).
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "checkpoint.h"
#include "data.h"
#include "phyir/model/training.h"
#include "stage_loss.h"

namespace phyir::eval {
struct GroundTruthView;
}

namespace phyir::model {

class Validator {
 public:
  // Loads the views (at most options.max_views: the in-memory subset validation keeps, in host
  // memory; each is moved to `device` for its pass). Off (enabled() false, with a log line
  // saying why) when options.every is 0, the split is empty, or `root` has no manifest or no
  // view in the split.
  Validator(const std::filesystem::path& root, const ValidationOptions& options, const ModelConfig& config,
            const torch::Device& device = torch::kCPU);

  bool enabled() const { return !views_.empty(); }
  size_t size() const { return views_.size(); }
  // After `epochs_done` of `epochs`: every options.every epochs and after the last.
  bool due(int epochs_done, int epochs) const;

  // `stage`: the networks the stage trains (its loss); `trained`: those trained before or now
  // (GSNet refines the maps, LNet's probes and re-render are scored, only when trained).
  ValidationRecord run(Networks& nets, const LossWeights& weights, StageNetworks stage, StageNetworks trained,
                       uint64_t seed) const;

  // The eval metrics a pass logs, in order (eval's names without relighting and counts).
  static const std::vector<std::string>& metric_names();
  // Whether `metric` (val_loss or one of metric_names()) improves upwards; throws
  // phyir::Error naming the known metrics when it is neither.
  static bool higher_is_better(const std::string& metric);

 private:
  ValidationOptions options_;
  ModelConfig config_;
  torch::Device device_;
  std::vector<ViewTensors> views_;       // at the network's resolutions, input units
  // Each view's ground truth as phyir eval reads it, read once (eval's type stays out of
  // this header: the model's tests do not see eval's headers).
  std::vector<std::shared_ptr<const eval::GroundTruthView>> truths_;
};

// The value of `metric` in a record (val_loss: its loss).
double metric_value(const ValidationRecord& record, const std::string& metric);

}  // namespace phyir::model
