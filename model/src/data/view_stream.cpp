// Streaming training batches (view_stream.h): torch::data's loader over TrainingBatches.
#include "view_stream.h"

#include <algorithm>
#include <exception>
#include <random>

#include "phyir/core/error.h"
#include "phyir/core/setting_error.h"

namespace phyir::model {

std::vector<size_t> epoch_order(size_t count, uint64_t seed, int epoch) {
  std::vector<size_t> order(count);
  for (size_t i = 0; i < count; ++i) order[i] = i;
  std::mt19937_64 shuffle_rng(seed * 1000003ULL + static_cast<uint64_t>(epoch));
  std::shuffle(order.begin(), order.end(), shuffle_rng);
  return order;
}

// --- EpochSampler -------------------------------------------------------------------------------

EpochSampler::EpochSampler(int epoch, std::vector<size_t> order, int64_t first_batch)
    : epoch_(epoch), order_(std::move(order)), first_(static_cast<size_t>(first_batch)), next_(0) {}

void EpochSampler::reset(torch::optional<size_t>) { next_ = 0; }

torch::optional<BatchRequest> EpochSampler::next(size_t batch_size) {
  const size_t begin = (first_ + next_) * batch_size;
  if (begin >= order_.size()) return torch::nullopt;
  ++next_;
  BatchRequest r;
  r.epoch = epoch_;
  r.indices.assign(order_.begin() + begin, order_.begin() + std::min(order_.size(), begin + batch_size));
  return r;
}

void EpochSampler::save(torch::serialize::OutputArchive&) const {
  fail("EpochSampler: not saved (a checkpoint resumes from its epoch and batch)");
}

void EpochSampler::load(torch::serialize::InputArchive&) {
  fail("EpochSampler: not loaded (a checkpoint resumes from its epoch and batch)");
}

// --- TrainingBatches ----------------------------------------------------------------------------

TrainingBatches::TrainingBatches(ManifestDataset views, const AugmentOptions& augment, int yaw_divisions,
                                 uint64_t seed, view::RadianceUnits units)
    : views_(std::move(views)), augment_(augment), divisions_(yaw_divisions), seed_(seed), units_(units) {}

Batch TrainingBatches::get_batch(BatchRequest request) {
  std::vector<ViewTensors> views;
  views.reserve(request.indices.size());
  for (size_t i : request.indices)
    views.push_back(augment_for_epoch(views_.get(i), i, augment_, divisions_, seed_, request.epoch, units_));
  return collate(views);
}

// --- BatchStream --------------------------------------------------------------------------------

BatchStream::BatchStream(TrainingBatches batches, StreamOptions options)
    : batches_(std::move(batches)), options_(options) {
  if (options_.workers < 0) fail_setting("workers", "{} must be 0 or more", options_.workers);
  if (options_.workers > 0 && options_.prefetch < 1)
    fail_setting("prefetch", "{} is too few: at least 1 batch is read ahead when there are workers ({} here)", options_.prefetch,
                 options_.workers);
}

void BatchStream::run_epoch(int epoch, const std::vector<size_t>& order, int64_t first_batch, int64_t batch,
                            const std::function<bool(Batch)>& step) {
  torch::data::DataLoaderOptions lo(static_cast<size_t>(batch));
  lo.workers(static_cast<size_t>(options_.workers)).enforce_ordering(true);
  // Jobs in flight: each is one batch being read or waiting; the consumer holds one more.
  if (options_.workers > 0) lo.max_jobs(static_cast<size_t>(options_.prefetch));
  auto loader = torch::data::make_data_loader(batches_, EpochSampler(epoch, order, first_batch), lo);
  try {
    for (auto it = loader->begin(); it != loader->end(); ++it) {
      Batch b = std::move(*it);  // the iterator keeps nothing: the step owns the batch
      if (!step(std::move(b))) break;
    }
  } catch (const torch::data::WorkerException& e) {
    std::rethrow_exception(e.original_exception);
  }
}

}  // namespace phyir::model
