#pragma once
// The exposure flags of the commands that write an LDR image from an HDR one (render, dataset
// generate and slurm, dataset import-futurehouse), one registration each: --exposure ("auto",
// core/auto_exposure.h, or a finite number of stops), and for the dataset's input.png the
// auto exposure's percentile and target, the per-view jitter and the OpenColorIO view
// (dataset::InputSettings, whose defaults the help shows). Settings recorded in the flag
// registry: "exposure", "view" (render's), "input.exposure_stops", "input.percentile",
// "input.target", "input.jitter_stops", "input.view" (the dataset's).
#include <optional>
#include <string>

#include <CLI/CLI.hpp>

#include "phyir/dataset/settings.h"

namespace phyir::cli {

// nullopt for "auto", else the stops; phyir::Error naming `flag` and the text otherwise.
std::optional<float> parse_exposure_flag(const std::string& text, const char* flag = "--exposure");

// --exposure of `image` ("color.png", "input.png"): sets `auto_exposure`, and `stops` when a
// number is given. `setting` is the name the library validating `stops` gives it.
CLI::Option* add_exposure_flag(CLI::App* cmd, bool& auto_exposure, float& stops, const std::string& image,
                               const std::string& setting);

// --view: the OpenColorIO view of `image` (Standard or Raw).
CLI::Option* add_view_flag(CLI::App* cmd, std::string& view, const std::string& image, const std::string& setting);

// input.png's: --exposure, --exposure-percentile, --exposure-target, --exposure-jitter, --view.
void add_input_exposure_flags(CLI::App* cmd, dataset::InputSettings& input);

}  // namespace phyir::cli
