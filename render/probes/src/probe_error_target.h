#pragma once
// Rendering a view's probes until their estimated error reaches a target
// (ProbeSettings::target_error): the estimate, the passes and their merge are docs/probes.md,
// "Accuracy as a target". Passes are merged by the directions each spent on a texel, never by
// sigma, which correlates with the value. The target bounds noise, not a bias.
#include <cstdint>
#include <functional>
#include <vector>

#include "phyir/render/probe_renderer.h"

namespace phyir::render {

// Each probe's pass count: 1 for the valid probes a first render of `subset` computed (every
// computed one when it is empty), 0 for the others, which no estimate counts.
std::vector<int> first_passes(const ProbeOutput& out, const std::vector<int>& subset);

// How far the texels' reported variances are off, from independent passes: over the texels
// two passes both hold, their luminances' squared differences against the sums of their
// reported variances (E[(a - b)^2] = Var a + Var b; docs/probes.md, "Accuracy as a target").
struct PassAgreement {
  double squared_difference = 0.0;
  double reported_variance = 0.0;
  uint64_t texels = 0;
  // The factor: 1 before two passes met (or where they report no variance).
  double factor() const;
};

// The estimated error of the probes holding passes, in luminance.
struct GridError {
  double variance_sum = 0.0;    // sum of the texels' sigma^2, times the agreement's factor
  double luminance_sum = 0.0;   // sum of the texels' luminance
  uint64_t texels = 0;
  double relative() const;      // sqrt(mean sigma^2) / mean luminance; 0 when dark or empty
};
GridError estimated_grid_error(const ProbeOutput& out, const std::vector<int>& passes, double factor = 1.0);

// The probes to render once more so that the grid's variance (times `factor`), each probe's
// projected from V / n to V / (n + 1), falls to (target x mean luminance)^2 per texel: largest
// reductions first, all of them when out of reach. `passes`: from first_passes, then merge_pass.
std::vector<int> probes_to_refine(const ProbeOutput& out, const std::vector<int>& passes, double target,
                                  double factor = 1.0);

// One valid probe in kCheckEvery (of those `passes` counts), every one on grids of fewer than
// kCheckEvery x kMinCheckProbes: a second pass over them measures the agreement before any
// stopping decision, so that a first pass whose sigma reads low does not end the refinement.
std::vector<int> probes_to_check(const std::vector<int>& passes);
constexpr int kCheckEvery = 8;
constexpr int kMinCheckProbes = 16;

// Folds a pass over `refined` into `total` (means weighted by each texel's directions where
// both hold them, else equal weights; sigma^2 likewise) and counts it in `passes`; the two's
// differences go into `agreement` (optional).
void merge_pass(const ProbeOutput& pass, const std::vector<int>& refined, std::vector<int>* passes, ProbeOutput* total,
                PassAgreement* agreement = nullptr);

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
