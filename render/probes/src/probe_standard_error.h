#pragma once
// Each probe texel's standard error as reported (probe_stderr.exr). A texel's own variance
// estimate (ProbeView::estimate) is noisy and tracks its mean where light is skewed, so the
// reported variance is half its own and half the mean of its 3x3 neighbourhood in the probe
// (columns wrap, rows clamp). docs/probes.md, "Per-texel standard error".
#include "phyir/core/image.h"
#include "phyir/view/probe_layout.h"

namespace phyir::render {

// `own`: the mosaic of each texel's own standard error (1 channel). Returns the reported one.
Image pooled_standard_error(const Image& own, const view::ProbeLayout& layout);

}  // namespace phyir::render
