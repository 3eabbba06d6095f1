#pragma once
// Rendering a view's probes until their estimated error reaches a target (ProbeSettings::target_error;
// docs/probes.md, "Accuracy as a target").
//
// The estimate: each texel's standard error sigma (probe_stderr.exr), pooled over the valid
// probes' texels as a relative RMSE, sqrt(mean sigma^2) / mean luminance. While it is above
// the target, the probes that hold most of the variance are rendered again as an independent
// pass (a fresh seed: its own directions and, in cache mode, its own cache, its reuse kernels
// shrunk: probe_pass_schedule.h), and each texel becomes the mean of its probe's passes
// weighted by the directions each spent on it (ProbeOutput::texel_samples; equal weights
// without them), sigma^2 likewise. Weights from the estimated sigmas would correlate with
// the values they weight (a pass that missed a bright path reports a low sigma too) and
// bias it. Which probes are refined looks at sigma only, never at the
// values a later pass adds. A later pass supersamples the texels its own first look or any
// earlier pass chose (ProbeOutput::texel_choices): a first look keeps its samples only where
// they missed a rare bright part, a loss every pass would repeat; once one pass found it,
// every later pass takes it, and the weights leave the passes that missed it behind.
//
// What the target bounds: the noise the standard error sees. A bias is not in sigma; the
// passes' schedule shrinks the part of it that comes from cache mode's kernels.
#include <cstdint>
#include <functional>
#include <vector>

#include "phyir/render/probe_renderer.h"

namespace phyir::render {

// How many passes each probe of the grid holds: 1 for the valid probes a first render of
// `subset` computed (every computed one when it is empty), 0 for the others, which no
// estimate counts.
std::vector<int> first_passes(const ProbeOutput& out, const std::vector<int>& subset);

// The estimated error of the probes holding passes, in luminance.
struct GridError {
  double variance_sum = 0.0;    // sum of the texels' sigma^2
  double luminance_sum = 0.0;   // sum of the texels' luminance
  uint64_t texels = 0;
  double relative() const;      // sqrt(mean sigma^2) / mean luminance; 0 when dark or empty
};
GridError estimated_grid_error(const ProbeOutput& out, const std::vector<int>& passes);

// The probes to render once more so that the grid's variance, projected as one more pass
// taking a probe's from V / n to V / (n + 1), falls to (target x mean luminance)^2 per
// texel: the largest reductions first, all with any variance when the target is out of
// reach. `passes`: each probe's pass count so far (first_passes, then merge_pass).
std::vector<int> probes_to_refine(const ProbeOutput& out, const std::vector<int>& passes, double target);

// Folds a pass over `refined` into `total` (means weighted by each texel's directions where
// both hold them, else equal weights; sigma^2 likewise) and counts it in `passes`.
void merge_pass(const ProbeOutput& pass, const std::vector<int>& refined, std::vector<int>* passes, ProbeOutput* total);

// Renders one independent pass of the given probes under the given settings, each texel
// supersampled by `choices` (the earlier passes' TexelChoice, the most any of them made).
using ProbePass = std::function<ProbeOutput(const ProbeSettings& settings, const std::vector<int>& subset,
                                            const std::vector<uint8_t>& choices)>;

// Refines `first` (a pass of `settings` over `subset`, empty: every probe) until its estimated error is at most
// settings.target_error (no refinement when it is 0) or kMaxErrorPasses passes were made; its statistics then include
// every pass and record the target, the error reached and the passes.
void refine_to_error(const ProbeSettings& settings, const std::vector<int>& subset, const ProbePass& render_pass,
                     ProbeOutput* first);

// At most this many passes over any probe: a target below what sigma can reach (a texel
// whose noise the standard error overstates) must not run unbounded.
constexpr int kMaxErrorPasses = 16;

}  // namespace phyir::render
