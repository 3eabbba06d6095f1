#pragma once
// The unit radiance (color.exr, probes.exr) is read, trained and scored in (docs/conventions.md
// "Radiance units"):
//   absolute  as color.exr and probes.exr hold it (W/(sr m^2));
//   input     times 2^exposure_stops of the view's input image (input_exposure.h): the scale in
//             which input.png's linear values are the radiance of the surfaces it shows. From an
//             auto-exposed LDR image the absolute brightness cannot be known, so the network is
//             trained in input units; scoring in them gives every view the scale of its input.
#include <string>
#include <vector>

namespace phyir::view {

enum class RadianceUnits { kAbsolute, kInput };

const std::vector<std::string>& radiance_units_names();  // "absolute", "input"
const std::string& radiance_units_name(RadianceUnits units);
// phyir::Error naming the value and the choices when `name` is none of them.
RadianceUnits parse_radiance_units(const std::string& name);

// What one unit of absolute radiance of a view exposed at `exposure_stops` is in `units`.
double radiance_scale(RadianceUnits units, double exposure_stops);

}  // namespace phyir::view
