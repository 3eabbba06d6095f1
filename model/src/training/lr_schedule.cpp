// Constant, step and cosine learning rates (lr_schedule.h).
#include "lr_schedule.h"

#include <algorithm>
#include <cmath>

#include "phyir/core/error.h"
#include "phyir/core/setting_error.h"

namespace phyir::model {

double LrSchedule::at(int64_t done) const {
  if (kind == "step") return base * std::pow(gamma, static_cast<double>(done / steps_per_epoch / step_epochs));
  if (kind == "cosine") {
    // From base at the first step to base x min_fraction at the last (Loshchilov & Hutter
    // 2017, one cycle, no restart); steps past the planned end keep the last rate.
    const double t = total_steps > 1 ? static_cast<double>(std::min(done, total_steps - 1)) / (total_steps - 1) : 1.0;
    return base * (min_fraction + (1.0 - min_fraction) * 0.5 * (1.0 + std::cos(M_PI * t)));
  }
  return base;
}

nlohmann::json LrSchedule::to_json() const {
  return {{"kind", kind}, {"step_epochs", step_epochs}, {"gamma", gamma}, {"min_fraction", min_fraction}};
}

LrSchedule make_schedule(const LrScheduleOptions& o, const nlohmann::json& saved, double base, int epochs,
                         int64_t steps_per_epoch) {
  LrSchedule s;
  s.base = base;
  s.steps_per_epoch = std::max<int64_t>(1, steps_per_epoch);
  s.total_steps = std::max<int64_t>(1, epochs * s.steps_per_epoch);
  if (o.kind.empty() && saved.is_object()) {
    s.kind = saved.at("kind").get<std::string>();
    s.step_epochs = saved.at("step_epochs").get<int>();
    s.gamma = saved.at("gamma").get<double>();
    s.min_fraction = saved.at("min_fraction").get<double>();
    return s;
  }
  s.kind = o.kind.empty() ? "constant" : o.kind;
  if (s.kind != "constant" && s.kind != "step" && s.kind != "cosine")
    fail_setting("schedule.kind", "'{}': expected constant, step or cosine", s.kind);
  s.step_epochs = o.step_epochs > 0 ? o.step_epochs : std::max(1, static_cast<int>(std::lround(epochs / 3.0)));
  s.gamma = o.gamma;
  s.min_fraction = o.min_fraction;
  if (!(s.gamma > 0.0 && s.gamma <= 1.0)) fail_setting("schedule.gamma", "{} must be in (0, 1]", s.gamma);
  if (!(s.min_fraction >= 0.0 && s.min_fraction <= 1.0))
    fail_setting("schedule.min_fraction", "{} must be in [0, 1]", s.min_fraction);
  return s;
}

}  // namespace phyir::model
