#pragma once
// Each probe texel's standard error as reported (probe_stderr.exr): its own variance estimate
// is noisy, so it is pooled with its neighbours' (docs/probes.md, "Per-texel standard error").
#include "phyir/core/image.h"
#include "phyir/view/probe_layout.h"

namespace phyir::render {

// `own`: the mosaic of each texel's own standard error (1 channel). Returns the reported one.
Image pooled_standard_error(const Image& own, const view::ProbeLayout& layout);

}  // namespace phyir::render
