#pragma once
// The learning rate of every optimiser step (docs/model.md "Learning-rate schedule"): a pure
// function of the step, so a resumed run takes the same rates as an uninterrupted one.
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>

#include "phyir/model/training.h"

namespace phyir::model {

struct LrSchedule {
  std::string kind = "constant";  // constant | step | cosine
  double base = 1e-4;             // the stage's rate (B.1) or the run's learning_rate
  int step_epochs = 1;            // step: the rate is multiplied by gamma every step_epochs epochs
  double gamma = 0.1;
  double min_fraction = 0.01;     // cosine: base x min_fraction at the last step
  int64_t steps_per_epoch = 1;
  int64_t total_steps = 1;        // cosine: epochs x steps_per_epoch

  // The rate of the step that follows `done` completed steps.
  double at(int64_t done) const;

  nlohmann::json to_json() const;  // kind and parameters (not base, steps: the run's own)
};

// The schedule of a run of `epochs` epochs of `steps_per_epoch` steps. `saved` (a checkpoint's
// "schedule", or null) supplies the kind and parameters when options.kind is empty. Throws
// phyir::Error on an unknown kind or a parameter out of range.
LrSchedule make_schedule(const LrScheduleOptions& options, const nlohmann::json& saved, double base, int epochs,
                         int64_t steps_per_epoch);

}  // namespace phyir::model
