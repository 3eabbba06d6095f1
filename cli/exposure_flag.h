#pragma once
// The `--exposure` flag of the commands that write an LDR image from an HDR one (render,
// dataset generate, dataset import-futurehouse): "auto" (core/auto_exposure.h) or a finite
// number of stops.
#include <optional>
#include <string>

namespace phyir::cli {

// nullopt for "auto", else the stops; phyir::Error naming `flag` and the text otherwise.
std::optional<float> parse_exposure_flag(const std::string& text, const char* flag = "--exposure");

}  // namespace phyir::cli
