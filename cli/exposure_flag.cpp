#include "exposure_flag.h"

#include <cmath>
#include <sstream>

#include "phyir/core/error.h"

namespace phyir::cli {

std::optional<float> parse_exposure_flag(const std::string& text, const char* flag) {
  if (text == "auto") return std::nullopt;
  std::istringstream in(text);
  float stops = 0.0f;
  if (!(in >> stops) || !in.eof() || !std::isfinite(stops))
    fail("{} '{}' must be 'auto' or a finite number of stops", flag, text);
  return stops;
}

}  // namespace phyir::cli
