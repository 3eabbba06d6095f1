#pragma once
// The toolkit's one equirectangular mapping (docs/conventions.md), implemented in
// core/equirect.h so that scene generation (the sky) shares it; named here in
// phyir::render for the renderer, the probes, the network's warp and the evaluation.
#include "phyir/core/equirect.h"

namespace phyir::render {

using phyir::equirect_direction;
using phyir::equirect_texel_solid_angle;
using phyir::equirect_uv;
using phyir::equirect_uv_pdf_to_solid_angle;

}  // namespace phyir::render
