#pragma once
// Streaming training data (docs/model-scale.md "Streaming"): the views of each batch read
// by worker threads from their folders (ManifestDataset, torch_dataset.h: load_view),
// augmented for the epoch (augment.h), collated (data.h), a few batches ahead of the step
// that uses them. Memory is bounded by the batch and the read-ahead, not the dataset: at most
// batch x (prefetch + 1) decoded views are alive (ViewCensus counts them; tested).
//
// Determinism: the epoch's order is a function of (seed, epoch) alone, batch k is always
// order[k*batch, (k+1)*batch), each batch is made by one thread from its request alone, and
// batches come back in request order (torch::data's ordered sequencer). So batches, and the
// parameters trained on them, do not depend on the worker count or on worker timing.
// Private header (torch types).
#include <torch/torch.h>

#include <cstdint>
#include <functional>
#include <vector>

#include "augment.h"
#include "data.h"
#include "torch_dataset.h"

namespace phyir::model {

struct StreamOptions {
  int workers = 2;   // threads decoding batches (0: read each batch on the training thread when due)
  int prefetch = 2;  // batches read ahead of the one being trained on (with workers; at least 1)
};

// The shuffled order of the views in `epoch`: a function of (seed, epoch, count) only, so a
// resumed run sees the same batches.
std::vector<size_t> epoch_order(size_t count, uint64_t seed, int epoch);

// One batch to read: the epoch (for the augmentation draws) and the views, in order.
struct BatchRequest {
  int epoch = 0;
  std::vector<size_t> indices;
  size_t size() const { return indices.size(); }
};

// The epoch's batches from a fixed order, starting at batch `first_batch` (a resumed epoch):
// batch k holds order[k*batch, (k+1)*batch), the last one possibly short.
class EpochSampler : public torch::data::samplers::Sampler<BatchRequest> {
 public:
  EpochSampler(int epoch, std::vector<size_t> order, int64_t first_batch);
  void reset(torch::optional<size_t> new_size = torch::nullopt) override;
  torch::optional<BatchRequest> next(size_t batch_size) override;
  // A sampler is rebuilt for every epoch from the checkpoint's (epoch, batch): nothing to save.
  void save(torch::serialize::OutputArchive& archive) const override;
  void load(torch::serialize::InputArchive& archive) override;

 private:
  int epoch_;
  std::vector<size_t> order_;
  size_t first_, next_;
};

// Training batches as a torch::data batch dataset: a request's views read by the dataset,
// each augmented by its (seed, epoch, view) draw, then collated.
class TrainingBatches : public torch::data::datasets::BatchDataset<TrainingBatches, Batch, BatchRequest> {
 public:
  TrainingBatches(ManifestDataset views, const AugmentOptions& augment, int yaw_divisions, uint64_t seed,
                  view::RadianceUnits units);
  Batch get_batch(BatchRequest request) override;
  torch::optional<size_t> size() const override { return views_.size(); }
  ManifestDataset& views() { return views_; }

 private:
  ManifestDataset views_;
  AugmentOptions augment_;
  int divisions_;
  uint64_t seed_;
  view::RadianceUnits units_;
};

// Runs the epochs' batches through a consumer, reading ahead with worker threads.
class BatchStream {
 public:
  // Throws phyir::SettingError naming the setting for a negative worker count or a prefetch below 1 with workers.
  BatchStream(TrainingBatches batches, StreamOptions options);

  // Calls `step` with the batches of `epoch` from `first_batch` on, in order, until it returns
  // false. Each batch is handed over (moved): the consumer releases it before the next one is
  // read, which keeps the bound. A worker's error is rethrown as it was thrown.
  void run_epoch(int epoch, const std::vector<size_t>& order, int64_t first_batch, int64_t batch,
                 const std::function<bool(Batch)>& step);

  const StreamOptions& options() const { return options_; }

 private:
  TrainingBatches batches_;
  StreamOptions options_;
};

}  // namespace phyir::model
