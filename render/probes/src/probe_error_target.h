#pragma once
// Rendering a view's probes until their estimated error reaches a target
// (ProbeSettings::target_error; docs/probes.md, "Accuracy as a target"). The estimate pools the
// texels' standard errors, sqrt(mean sigma^2) / mean luminance. Passes are independent (a seed
// of their own; kernels shrunk: probe_pass_schedule.h) and merged weighted by the directions
// each spent on a texel, never by sigma, which correlates with the value. A later pass
// supersamples what any pass chose. The target bounds the noise sigma sees, not a bias.
#include <cstdint>
#include <functional>
#include <vector>

#include "phyir/render/probe_renderer.h"

namespace phyir::render {

// Each probe's pass count: 1 for the valid probes a first render of `subset` computed (every
// computed one when it is empty), 0 for the others, which no estimate counts.
std::vector<int> first_passes(const ProbeOutput& out, const std::vector<int>& subset);

// The estimated error of the probes holding passes, in luminance.
struct GridError {
  double variance_sum = 0.0;    // sum of the texels' sigma^2
  double luminance_sum = 0.0;   // sum of the texels' luminance
  uint64_t texels = 0;
  double relative() const;      // sqrt(mean sigma^2) / mean luminance; 0 when dark or empty
};
GridError estimated_grid_error(const ProbeOutput& out, const std::vector<int>& passes);

// The probes to render once more so that the grid's variance, each probe's projected from
// V / n to V / (n + 1), falls to (target x mean luminance)^2 per texel: largest reductions
// first, all of them when out of reach. `passes`: from first_passes, then merge_pass.
std::vector<int> probes_to_refine(const ProbeOutput& out, const std::vector<int>& passes, double target);

// Folds a pass over `refined` into `total` (means weighted by each texel's directions where
// both hold them, else equal weights; sigma^2 likewise) and counts it in `passes`.
void merge_pass(const ProbeOutput& pass, const std::vector<int>& refined, std::vector<int>* passes, ProbeOutput* total);

// Renders one independent pass of the given probes under the given settings, each texel
// supersampled by `choices` (the earlier passes' TexelChoice, the most any of them made).
using ProbePass = std::function<ProbeOutput(const ProbeSettings& settings, const std::vector<int>& subset,
                                            const std::vector<uint8_t>& choices)>;

// Refines `first` (a pass of `settings` over `subset`, empty: every probe) until its estimated
// error is at most settings.target_error (0: no refinement) or kMaxErrorPasses were made; its
// statistics then include every pass and record the target, the error reached and the passes.
void refine_to_error(const ProbeSettings& settings, const std::vector<int>& subset, const ProbePass& render_pass,
                     ProbeOutput* first);

// At most this many passes over any probe: a target below what sigma can reach must end.
constexpr int kMaxErrorPasses = 16;

}  // namespace phyir::render
