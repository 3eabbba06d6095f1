#include "bench_probes_lighting.h"

#include <cmath>

#include "phyir/core/error.h"
#include "phyir/eval/pixel_metrics.h"
#include "phyir/eval/probe_set.h"

namespace phyir::cli {

namespace {

// A 1 x 1 grid holding probe k of `lit` (eval::probe_ssim of one probe).
view::ProbeMosaic single_probe(const view::ProbeMosaic& lit, int k) {
  view::ProbeMosaic one;
  one.layout = lit.layout;
  one.layout.grid_width = one.layout.grid_height = 1;
  one.radiance = lit.probe(0, k);
  one.mask = Image(1, 1, 1, 1.0f);
  return one;
}

}  // namespace

LitProbes light_probes(const Image& strip, int res_height, int res_width, const eval::RelightSettings& settings) {
  if (res_width <= 0 || strip.width % res_width != 0 || strip.height != res_height || strip.channels < 3)
    fail("lighting metrics: a strip of {}x{}x{} is not probes of {}x{} RGB side by side", strip.width, strip.height,
         strip.channels, res_height, res_width);
  LitProbes lit;
  const int count = strip.width / res_width;
  lit.mosaic.layout = view::ProbeLayout{1, count, res_height, res_width};
  lit.mosaic.radiance = Image(strip.width, strip.height, 3);
  for (int y = 0; y < strip.height; ++y)
    for (int x = 0; x < strip.width; ++x)
      for (int ch = 0; ch < 3; ++ch) lit.mosaic.radiance.at(x, y, ch) = strip.at(x, y, ch);
  lit.mosaic.mask = Image(count, 1, 1, 1.0f);
  const auto& materials = eval::sphere_materials();
  lit.spheres.resize(size_t(count));
  for (int k = 0; k < count; ++k)
    for (size_t m = 0; m < kSphereMaterials; ++m)
      lit.spheres[size_t(k)][m] = eval::relight_sphere(lit.mosaic.probe(0, k), materials[m], settings);
  return lit;
}

LightingMetrics lighting_metrics(const LitProbes& measured, const LitProbes& reference) {
  if (measured.spheres.size() != reference.spheres.size())
    fail("lighting metrics: {} probes measured against {} reference probes", measured.spheres.size(),
         reference.spheres.size());
  LightingMetrics out;
  const size_t count = reference.spheres.size();
  out.probes = long(count);
  out.probe_mae.resize(count);
  // Pooled over the probes' sphere pixels as eval's score_relighting pools over positions.
  for (size_t m = 0; m < kSphereMaterials; ++m) {
    double abs = 0.0, sq = 0.0, magnitude = 0.0, n = 0.0;
    for (size_t k = 0; k < count; ++k) {
      const eval::RelitSphere &a = measured.spheres[k][m], &b = reference.spheres[k][m];
      const double pixels = double(eval::count_mask(b.mask)) * 3.0;
      out.probe_mae[k][m] = eval::masked_mae(a.color, b.color, b.mask);
      abs += out.probe_mae[k][m] * pixels;
      sq += eval::masked_mse(a.color, b.color, b.mask) * pixels;
      magnitude += eval::masked_mae(b.color, Image(b.color.width, b.color.height, b.color.channels), b.mask) * pixels;
      n += pixels;
    }
    out.mae[m] = n > 0 ? abs / n : 0.0;
    out.rmse[m] = n > 0 ? std::sqrt(sq / n) : 0.0;
    out.relative_mae[m] = magnitude > 0 ? abs / magnitude : 0.0;
  }
  out.ssim = eval::probe_ssim(measured.mosaic, reference.mosaic).ssim;
  for (size_t k = 0; k < count; ++k)
    out.probe_ssim.push_back(
        eval::probe_ssim(single_probe(measured.mosaic, int(k)), single_probe(reference.mosaic, int(k))).ssim);
  return out;
}

LightingMetrics scaled_metrics(const LightingMetrics& absolute, const LitProbes& measured, const LitProbes& reference,
                               double factor) {
  LightingMetrics out = absolute;
  for (size_t m = 0; m < kSphereMaterials; ++m) out.mae[m] *= factor, out.rmse[m] *= factor;
  for (auto& probe : out.probe_mae)
    for (double& v : probe) v *= factor;
  const view::ProbeMosaic a = measured.mosaic.scaled(factor), b = reference.mosaic.scaled(factor);
  out.ssim = eval::probe_ssim(a, b).ssim;
  for (size_t k = 0; k < out.probe_ssim.size(); ++k)
    out.probe_ssim[k] = eval::probe_ssim(single_probe(a, int(k)), single_probe(b, int(k))).ssim;
  return out;
}

nlohmann::json LightingMetrics::to_json() const {
  nlohmann::json j;
  const auto& materials = eval::sphere_materials();
  for (size_t m = 0; m < kSphereMaterials; ++m) {
    j[materials[m].key + "_mae"] = mae[m];
    j[materials[m].key + "_rmse"] = rmse[m];
    j["relative_" + materials[m].key + "_mae"] = relative_mae[m];
  }
  j["probe_ssim"] = ssim;
  j["probes"] = probes;
  nlohmann::json per_probe = nlohmann::json::array();
  for (size_t k = 0; k < probe_mae.size(); ++k) {
    nlohmann::json p = {{"probe_ssim", probe_ssim[k]}};
    for (size_t m = 0; m < kSphereMaterials; ++m) p[materials[m].key + "_mae"] = probe_mae[k][m];
    per_probe.push_back(p);
  }
  j["per_probe"] = per_probe;
  return j;
}

}  // namespace phyir::cli
