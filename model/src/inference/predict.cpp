// GMNet, GSNet, LNet and the rendering layer in sequence (predict.h).
#include "predict.h"

#include <chrono>

#include "stage_loss.h"

namespace phyir::model {

ModelOutput predict(Networks& nets, const ModelConfig& c, const torch::Tensor& image, bool use_gsnet, bool use_light) {
  using Clock = std::chrono::steady_clock;
  const auto ms = [](Clock::time_point a, Clock::time_point b) {
    return std::chrono::duration<double, std::milli>(b - a).count();
  };
  ModelOutput out;
  const auto t0 = Clock::now();
  out.maps = nets.gmnet->forward(image);
  const auto t1 = Clock::now();
  if (use_gsnet) out.maps = nets.gsnet->forward(image, out.maps);
  const auto t2 = Clock::now();
  if (use_light) {
    const LightResult light = run_light(nets, c, image, out.maps);
    out.probes = light.probes;
    out.rerender = light.render.image;
  }
  const auto t3 = Clock::now();
  out.gmnet_ms = ms(t0, t1);
  out.gsnet_ms = ms(t1, t2);
  out.light_ms = ms(t2, t3);
  return out;
}

}  // namespace phyir::model
