// A stage's forward pass and losses (stage_loss.h).
#include "stage_loss.h"

#include "batch_share.h"
#include "losses.h"
#include "probe_weights.h"
#include "phyir/core/error.h"
#include "phyir/view/view_files.h"

namespace phyir::model {

namespace {

torch::Tensor area(const torch::Tensor& x, int h, int w) { return resize(x, h, w); }

void add_gm_losses(StepLoss& L, const LossWeights& w, const GMOutput& p, const Batch& b) {
  L.add("basecolor", w.base_color, l2_loss(p.base_color, b.base_color, b.mask));
  L.add("roughness", w.roughness, l2_loss(p.roughness, b.roughness, b.mask));
  L.add("metalness", w.metalness, metalness_loss(p.metalness, b.metalness, b.mask));
  L.add("depth", w.depth, berhu_loss(p.depth, b.depth, b.mask));
  L.add("normal", w.normal, normal_cosine_loss(p.normal, b.normal, b.mask));
  if (w.gradient != 0.0) {
    L.add("gradient", w.gradient,
          gradient_loss(p.base_color, b.base_color, b.mask) + gradient_loss(p.roughness, b.roughness, b.mask) +
              gradient_loss(p.normal, b.normal, b.mask) + gradient_loss(p.metalness, b.metalness, b.mask));
  }
}

// The probe loss's texel weights: undefined (unweighted) unless the stderr weighting is on.
torch::Tensor probe_weights(const LossWeights& w, const Batch& b) {
  if (!w.probe_stderr) return {};
  if (!b.probe_stderr.defined()) {
    std::string folders;
    for (const std::string& id : b.without_probe_stderr) folders += (folders.empty() ? "" : ", ") + id;
    fail("probe loss weighted by standard error: view folder(s) {} have no {} (render the probes again, or "
         "train unweighted)", folders, view::kProbeStderrFile);
  }
  return probe_stderr_weights(b.probes, b.probe_stderr, b.probe_mask);
}

void add_light_losses(StepLoss& L, const LossWeights& w, const ModelConfig& c, const LightResult& r,
                      const GMOutput& gm, const Batch& b) {
  if (!b.probes.defined()) fail("stage needs probes: a view folder has no {}", view::kProbesFile);
  L.add("probe", w.probe, probe_ssim_loss(r.log_probes, torch::log1p(b.probes), b.probe_mask, probe_weights(w, b)));
  if (w.coherence != 0.0)
    L.add("coherence", w.coherence,
          spatial_coherence_loss(r.log_probes, area(gm.depth, c.render_height, c.render_width), b.render_mask));
  L.add("render", w.render, l2_loss(r.render.image, b.color_lo, b.render_mask));
}

void add_gs_losses(StepLoss& L, const LossWeights& w, const GMOutput& refined, const Batch& b) {
  L.add("basecolor", w.base_color, l2_loss(refined.base_color, b.base_color, b.mask));
  L.add("roughness", w.roughness, l2_loss(refined.roughness, b.roughness, b.mask));
  L.add("normal", w.normal, normal_cosine_loss(refined.normal, b.normal, b.mask));
}

}  // namespace

StageNetworks StageNetworks::of(Stage s) {
  StageNetworks t;
  t.gmnet = s == Stage::kGMNet || s == Stage::kJoint;
  t.lnet = s == Stage::kLNet || s == Stage::kJoint;
  t.gsnet = s == Stage::kGSNet;
  return t;
}

void StepLoss::add(const std::string& name, double weight, const torch::Tensor& value) {
  if (weight == 0.0) return;
  parts.emplace_back(name, value.detach());
  total = total.defined() ? total + weight * value : weight * value;
}

std::string format_parts(const StepLoss& L) {
  std::string s;
  for (const auto& [name, v] : L.parts) s += fmt::format("{}{} {:.5g}", s.empty() ? "" : ", ", name, v.item<double>());
  return s;
}

torch::Tensor linear_probes(const torch::Tensor& log_probes) {
  // clamp_max's gradient needs its input, not its result: expm1_ may overwrite the result.
  return log_probes.clamp_max(30.0).expm1_();
}

LightResult run_light(Networks& nets, const ModelConfig& c, const torch::Tensor& image, const GMOutput& gm) {
  LightResult r;
  const int Hr = c.render_height, Wr = c.render_width;
  r.log_probes = nets.lnet->forward(lnet_input(image, gm, Hr, Wr));
  r.probes = linear_probes(r.log_probes);
  RenderSettings rs;
  rs.diffuse_samples = c.diffuse_samples;
  rs.specular_samples = c.specular_samples;
  rs.first_stream = batch_first_view() * Hr * Wr;
  r.render = render_layer(normalize_channels(area(gm.normal, Hr, Wr)), area(gm.base_color, Hr, Wr),
                          area(gm.roughness, Hr, Wr), area(gm.metalness, Hr, Wr), r.probes, rs);
  return r;
}

StepLoss stage_loss(Networks& nets, const ModelConfig& c, const LossWeights& w, StageNetworks train,
                    const Batch& b) {
  StepLoss L;
  GMOutput gm;
  if (train.gmnet) {
    gm = nets.gmnet->forward(b.image);
  } else {
    torch::NoGradGuard no_grad;
    gm = nets.gmnet->forward(b.image);
  }
  if (train.gmnet) add_gm_losses(L, w, gm, b);
  if (train.lnet) add_light_losses(L, w, c, run_light(nets, c, b.image, gm), gm, b);
  if (train.gsnet) add_gs_losses(L, w, nets.gsnet->forward(b.image, gm), b);
  if (!L.total.defined()) fail("every loss weight of the stage is 0");
  return L;
}

}  // namespace phyir::model
