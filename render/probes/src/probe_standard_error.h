#pragma once
// Each probe texel's standard error as the renderer reports it (probe_stderr.exr).
//
// A texel's own samples estimate the variance of its mean (ProbeView::estimate: the collapsed
// strata's differences, else the samples' spread). With tens of samples of a skewed quantity
// (rare bright paths) that estimate is noisy and tracks the estimate itself: a texel that
// missed its bright paths reports both a low mean and a low variance, so its interval is too
// narrow. The reported variance therefore shrinks each texel's own estimate towards the mean of
// its 3x3 neighbourhood in the probe (columns wrap, rows clamp): half each. Neighbours see the
// same light a texel's width away, so the pooled part has ~9x the samples; the own half keeps
// a texel on an edge (a light's outline) its larger variance. Measured in path mode
// (tests/probes/probe_stderr_test.cpp, docs/probes.md "Per-texel standard error").
#include "phyir/core/image.h"
#include "phyir/view/probe_layout.h"

namespace phyir::render {

// `own`: the mosaic of each texel's own standard error (1 channel). Returns the reported one.
Image pooled_standard_error(const Image& own, const view::ProbeLayout& layout);

}  // namespace phyir::render
