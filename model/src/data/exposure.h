#pragma once
// The unit of the radiance targets and the input image's sRGB curve in torch (docs/model.md
// "Exposure and units"; the exposure record and the units: view/input_exposure.h,
// view/radiance_units.h). Training scales the radiance targets (probes, color.exr) by
// 2^stops of each view's input: the "input units". Private header (torch types).
#include <torch/torch.h>


#include "phyir/model/training.h"
#include "phyir/view/input_exposure.h"
#include "phyir/view/radiance_units.h"

namespace phyir::model {

// The unit a run trains LNet's targets in: ModelConfig::target_units "input" (the default) or
// "absolute" (targets as the files hold them, a study switch for the with/without comparison).
// Anything else: phyir::Error naming the value.
view::RadianceUnits target_radiance(const ModelConfig& config);

// The sRGB curve exactly as config/phyir.ocio applies it (ExponentWithLinearTransform, gamma
// 2.4, offset 0.055: its linear segment is the tangent from the origin, slope 12.923, not
// IEC's rounded 12.92), so decode(input.png) is the linear image OpenColorIO encoded.
torch::Tensor srgb_encode(const torch::Tensor& linear);   // clips to [0, 1] first (Standard view)
torch::Tensor srgb_decode(const torch::Tensor& encoded);

// An LDR input as if written at `factor` times its exposure: decoded to linear, multiplied,
// clipped to [0, 1], encoded again (raw_view: no curve). A pixel input.png had clipped holds
// `factor` afterwards: its radiance above the clip point was lost when input.png was written.
torch::Tensor reexpose_ldr(const torch::Tensor& image, double factor, bool raw_view);

}  // namespace phyir::model
