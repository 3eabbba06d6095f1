#pragma once
// One stage's training run (appendix B.1) as named steps: settle the settings (from the
// options, or the checkpoint being resumed), build the networks and the optimiser, load the
// data (streamed: view_stream.h), then epochs of steps with validation passes, checkpoints and
// logs. train() in
// training.h is Trainer(options).run(). Private header (torch types).
#include <torch/torch.h>

#include <cmath>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "checkpoint.h"
#include "data.h"
#include "process_group.h"
#include "lr_schedule.h"
#include "phyir/core/stopwatch.h"
#include "phyir/model/training.h"
#include "stage_loss.h"
#include "train_log.h"
#include "validation.h"
#include "view_stream.h"

namespace phyir::model {

// The best validation so far, kept in every checkpoint's metadata so a resume continues it.
struct BestSoFar {
  std::string metric;
  double value = std::nan("");
  int epoch = 0;
  int64_t step = 0;
  bool better(double candidate, bool higher_is_better) const;
  nlohmann::json to_json() const;
};

class Trainer {
 public:
  explicit Trainer(const TrainOptions& options);
  TrainSummary run();

 private:
  void settle_settings();     // learning rate, batch, weights, configuration
  void join_ranks();          // data-parallel: the process group (no-op for one process)
  void build_networks();      // networks, which of them train, optimiser, resumed state
  void load_data();           // training views, validator, schedule, logs
  bool run_epoch(int epoch);  // false when max_steps stopped the run inside it
  double run_step(int epoch, int64_t batch_index, const Batch& batch);
  void log_step(int epoch, int64_t batch_index, double loss, const StepLoss& parts, double lr, double step_seconds);
  void validate(int epoch_done);
  nlohmann::json meta(int epoch, int64_t batch) const;
  void set_modes(bool training);
  void write_summary();
  bool lead() const { return rank_ == 0; }  // the rank that validates and writes every file

  const TrainOptions& o_;
  std::string stage_name_;
  StageDefaults defaults_;
  StageNetworks stage_;
  std::filesystem::path out_, checkpoint_path_;
  nlohmann::json resumed_;  // the checkpoint's metadata when resuming

  double lr_ = 0.0;
  int batch_size_ = 0;
  LossWeights weights_;
  ModelConfig config_;
  nlohmann::json trained_;

  std::unique_ptr<Networks> nets_;
  std::unique_ptr<torch::optim::Adam> opt_;  // one parameter group: the stage's networks
  int start_epoch_ = 0;
  int64_t start_batch_ = 0, global_step_ = 0;

  torch::Device device_ = torch::kCPU;
  std::unique_ptr<ProcessGroup> group_;  // null for one process
  int rank_ = 0, ranks_ = 1;
  std::unique_ptr<BatchStream> stream_;  // the training views, read as batches are due
  int64_t views_ = 0;
  int64_t batch_ = 1, batches_per_epoch_ = 1;  // the global batch (all ranks' views of a step)
  int yaw_divisions_ = 1;
  std::unique_ptr<Validator> validator_;
  LrSchedule schedule_;
  BestSoFar best_;
  std::unique_ptr<CsvLog> step_log_, val_log_;

  TrainSummary summary_;
  double epoch_loss_sum_ = 0.0;
  int64_t epoch_steps_ = 0;
  Stopwatch start_time_;
};

}  // namespace phyir::model
