#pragma once
// The input image's exposure and the unit of the radiance targets (docs/model.md "Exposure
// and units"). A dataset view's input.png is sRGB(clip(2^stops x color.exr)), `stops` chosen
// per view (auto exposure) and recorded in its view.json (input.exposure_stops). From an
// auto-exposed LDR image the absolute brightness cannot be known, so training scales the
// radiance targets (probes, color.exr) by 2^stops: the "input units", in which input.png's
// linear values are the radiance of the surfaces it shows. Private header (torch types).
#include <torch/torch.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "phyir/model/training.h"

namespace phyir::model {

// The unit load_view returns radiance (probes, colour) in.
enum class Radiance {
  kAbsolute,    // as color.exr and probes.exr hold it
  kInputUnits,  // x 2^exposure_stops: input.png's linear scale
};

// The unit a run trains LNet's targets in: ModelConfig::target_units "input" (the default) or
// "absolute" (targets as the files hold them: the behaviour before the exposure fix, kept as a
// study switch for the with/without comparison). Anything else: phyir::Error naming the value.
Radiance target_radiance(const ModelConfig& config);

struct InputExposure {
  double stops = 0.0;
  bool recorded = false;  // false: view.json has none and 0 stops is assumed
  bool raw_view = false;  // input.png skipped the sRGB curve (`phyir dataset generate --view Raw`)
  double factor() const { return std::exp2(stops); }
};

// A view folder's input exposure from its view.json (`input.exposure_stops`, `input.view`).
// Without one (a `phyir render` folder, a hand-made folder): 0 stops, not recorded. That is
// exact when the folder has no input.png (load_view then makes the input from color.exr at
// 0 stops); an input.png without view.json is taken as written at 0 stops (load_view warns).
// A view.json that is not valid JSON or holds a non-numeric exposure: phyir::Error naming it.
InputExposure read_input_exposure(const std::filesystem::path& view_dir);

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
