#include "phyir/view/radiance_units.h"

#include <cmath>

#include "phyir/core/error.h"

namespace phyir::view {

const std::vector<std::string>& radiance_units_names() {
  static const std::vector<std::string> names = {"absolute", "input"};
  return names;
}

const std::string& radiance_units_name(RadianceUnits units) { return radiance_units_names()[size_t(units)]; }

RadianceUnits parse_radiance_units(const std::string& name) {
  const auto& names = radiance_units_names();
  for (size_t k = 0; k < names.size(); ++k)
    if (names[k] == name) return RadianceUnits(k);
  fail("radiance units '{}': expected absolute or input", name);
}

double radiance_scale(RadianceUnits units, double exposure_stops) {
  return units == RadianceUnits::kInput ? std::exp2(exposure_stops) : 1.0;
}

}  // namespace phyir::view
