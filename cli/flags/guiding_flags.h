#pragma once
// The path-guiding flags (docs/guiding.md, "Knobs"): --guiding and its two knobs, each bound to
// the render::GuidingSettings field it sets, showing that field's value as its default, and
// recorded in the flag registry under the setting names GuidingSettings::validate reports
// ("guiding.bsdf_fraction", "guiding.spatial_threshold").
#include <CLI/CLI.hpp>

#include "phyir/render/guided_render.h"

namespace phyir::cli {

void add_guiding_flags(CLI::App* cmd, render::GuidingSettings& guiding);

}  // namespace phyir::cli
