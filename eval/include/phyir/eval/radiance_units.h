#pragma once
// The unit the radiance metrics (re-render MSE, probe SSIM, relighting) are scored in
// (`phyir eval --radiance`, docs/eval.md "Radiance units"):
//   absolute  color.exr's and probes.exr's own unit (W/(sr m^2)), the default;
//   input     the view's input image's unit: both sides times 2^exposure_stops (view.json),
//             as the network is trained to predict (docs/model.md "Exposure and units").
// Absolute errors are dominated by the brightest views (a sunlit view can be 2^10 times a
// lamp-lit one); input units give every view the scale of its own input image.
#include <string>
#include <vector>

#include "phyir/eval/probe_set.h"

namespace phyir::eval {

enum class RadianceUnits { kAbsolute, kInput };

const std::vector<std::string>& radiance_units_names();  // "absolute", "input"
const std::string& radiance_units_name(RadianceUnits units);
// phyir::Error naming the value and the choices when `name` is none of them.
RadianceUnits parse_radiance_units(const std::string& name);

// What one unit of absolute radiance of a view with this exposure is in `units`.
double radiance_scale(RadianceUnits units, float exposure_stops);

// `probes` with every texel times `scale`.
ProbeSet scaled_probe_set(const ProbeSet& probes, double scale);

}  // namespace phyir::eval
