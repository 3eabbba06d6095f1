// The rendering layer on a view folder's own ground truth (`phyir infer`'s render-layer check).
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "host_memory.h"
#include "data.h"
#include "phyir/core/error.h"
#include "phyir/core/image_io.h"
#include "phyir/core/log.h"
#include "phyir/model/training.h"
#include "phyir/view/probe_mosaic.h"
#include "phyir/view/view_files.h"
#include "render_layer.h"

namespace fs = std::filesystem;
using nlohmann::json;

namespace phyir::model {

namespace {

// The view folder's resolutions: the probe grid (probe_mask.exr) and its texels (probes.exr).
ModelConfig view_config(const fs::path& dir) {
  if (!view::has_probes(dir)) fail("{}: no {} (the render-layer check needs the view's probes)", dir.string(), view::kProbesFile);
  const view::ProbeLayout layout = view::read_probe_mosaic(dir).layout;
  ModelConfig c;
  c.render_height = layout.grid_height;
  c.render_width = layout.grid_width;
  c.probe_height = layout.res_height;
  c.probe_width = layout.res_width;
  const phyir::Image color_img = read_image(dir / view::kColorFile);
  c.input_height = color_img.height;
  c.input_width = color_img.width;
  return c;
}

RenderCheckResult compare(const torch::Tensor& I, const torch::Tensor& Ir, const torch::Tensor& mask) {
  const double n = mask.sum().item<double>() * 3.0;
  RenderCheckResult res;
  res.width = static_cast<int>(I.size(3));
  res.height = static_cast<int>(I.size(2));
  res.pixels = static_cast<int64_t>(mask.sum().item<double>());
  if (n > 0) {
    res.mse = ((I - Ir).square() * mask).sum().item<double>() / n;
    res.relative_mse = ((I - Ir).square() * mask).sum().item<double>() / (I.square() * mask).sum().item<double>();
    res.mean_color = (I * mask).sum().item<double>() / n;
    res.mean_rerender = (Ir * mask).sum().item<double>() / n;
    res.mean_abs_error = ((I - Ir).abs() * mask).sum().item<double>() / n;
  }
  return res;
}

void write_check(const RenderCheckOptions& o, const ModelConfig& c, const RenderOutput& r, const torch::Tensor& mask,
                 const RenderCheckResult& res) {
  const fs::path out(o.out_dir);
  fs::create_directories(out);
  write_tensor_image(out / "rerender.exr", r.image[0], {"R", "G", "B"});
  write_tensor_image(out / "rerender_diffuse.exr", r.diffuse[0], {"R", "G", "B"});
  write_tensor_image(out / "rerender_specular.exr", r.specular[0], {"R", "G", "B"});
  write_tensor_image(out / "compare_mask.exr", mask[0].to(torch::kFloat), {"Y"});
  const json j = {{"view", o.view_dir}, {"width", res.width}, {"height", res.height}, {"probe_width", c.probe_width},
                  {"probe_height", c.probe_height}, {"diffuse_samples", o.diffuse_samples},
                  {"specular_samples", o.specular_samples}, {"pixels", res.pixels}, {"mse", res.mse},
                  {"relative_mse", res.relative_mse}, {"mean_color", res.mean_color},
                  {"mean_rerender", res.mean_rerender}, {"mean_abs_error", res.mean_abs_error},
                  {"radiance", "absolute (color.exr's unit)"}};
  std::ofstream(out / "check.json") << j.dump(2) << "\n";
}

}  // namespace

RenderCheckResult check_render_layer(const RenderCheckOptions& o) {
  init_logging();
  set_threads(o.threads);
  retain_freed_memory();
  torch::manual_seed(o.seed);
  torch::NoGradGuard no_grad;
  const ModelConfig c = view_config(o.view_dir);
  const ViewTensors v = load_view(o.view_dir, c);
  auto lo = [&](const torch::Tensor& x) { return resize(x.unsqueeze(0), c.render_height, c.render_width); };
  RenderSettings rs;
  rs.diffuse_samples = o.diffuse_samples;
  rs.specular_samples = o.specular_samples;
  const torch::Tensor normal = torch::nn::functional::normalize(
      lo(v.normal), torch::nn::functional::NormalizeFuncOptions().dim(1).eps(1e-6));
  const RenderOutput r = render_layer(normal, lo(v.base_color), lo(v.roughness), lo(v.metalness),
                                      v.probes.unsqueeze(0), rs);
  const torch::Tensor mask = (v.render_mask * v.probe_mask).unsqueeze(0).to(torch::kDouble);  // [1,1,H,W]
  const RenderCheckResult res = compare(v.color_lo.unsqueeze(0).to(torch::kDouble), r.image.to(torch::kDouble), mask);
  if (!o.out_dir.empty()) write_check(o, c, r, mask, res);
  return res;
}

}  // namespace phyir::model
