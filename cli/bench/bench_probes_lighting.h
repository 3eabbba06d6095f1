#pragma once
// `phyir bench probes`' lighting metrics: the probes' error as the paper's evaluation sees it
// (docs/probes_lighting_metrics.md). Between two strips of probes (probes side by side,
// render/probe_study_breakdown.h's probe_strip), exactly what `phyir eval` computes between
// a prediction and the ground truth (eval/src/evaluate_view.cpp): Table 10's spheres relit by
// each probe (eval::relight_sphere, eval's default sphere settings, the same seed on both
// sides), MAE and RMSE over the sphere's pixels and RGB pooled over the probes, in the probes'
// own unit (linear radiance: eval's absolute units); and eval::probe_ssim, the mean over
// probes of SSIM of log(1 + L).
#include <array>
#include <vector>

#include <nlohmann/json.hpp>

#include "phyir/core/image.h"
#include "phyir/eval/relight.h"
#include "phyir/view/probe_mosaic.h"

namespace phyir::cli {

constexpr size_t kSphereMaterials = 3;  // eval::sphere_materials(): diffuse, matte silver, mirror silver

// A strip's probes and the spheres each one lights: relit once, compared with many.
struct LitProbes {
  view::ProbeMosaic mosaic;  // the strip as a 1 x N grid of valid probes (eval::probe_ssim's input)
  // spheres[k][m]: probe k lighting eval::sphere_materials()[m].
  std::vector<std::array<eval::RelitSphere, kSphereMaterials>> spheres;
};

// Relights every probe of `strip` (res_height x res_width texels each) with every material.
LitProbes light_probes(const Image& strip, int res_height, int res_width, const eval::RelightSettings& settings);

struct LightingMetrics {
  std::array<double, kSphereMaterials> mae{};           // as eval's relight_<material>_mae
  std::array<double, kSphereMaterials> rmse{};          // as eval's relight_<material>_rmse
  // mae / the mean radiance of the reference side's spheres (over their pixels and RGB): the
  // same error without the scene's brightness.
  std::array<double, kSphereMaterials> relative_mae{};
  double ssim = 0.0;  // as eval's probe_ssim
  long probes = 0;
  // Per probe, in strip order: MAE per material and SSIM.
  std::vector<std::array<double, kSphereMaterials>> probe_mae;
  std::vector<double> probe_ssim;

  // {"diffuse_mae", ..., "relative_diffuse_mae", ..., "probe_ssim", "probes", "per_probe"}.
  nlohmann::json to_json() const;
};

// `measured` against `reference`; both lit with the same settings.
LightingMetrics lighting_metrics(const LitProbes& measured, const LitProbes& reference);

// `absolute` (lighting_metrics of the two) with both sides' radiance times `factor`, as
// `phyir eval --radiance input` scores: the spheres' MAE and RMSE times `factor` (relighting
// is linear in the probe: the same seed draws the same samples from a scaled environment),
// the relative MAE unchanged, probe SSIM recomputed on the scaled probes (log(1 + L) is not
// linear).
LightingMetrics scaled_metrics(const LightingMetrics& absolute, const LitProbes& measured, const LitProbes& reference,
                               double factor);

}  // namespace phyir::cli
