#pragma once
// The sampling flags, one registration each for every command that renders: --spp,
// --max-bounces, --light-subpaths, --seed and --threads. Each binds to the field it sets, shows that field's
// value as its default (the settings struct's, render/render_view.h and path_tracer.h) and
// records the setting it sets ("spp", "max_bounces", "seed", "threads") in the flag registry.
#include <cstdint>

#include <CLI/CLI.hpp>

#include "phyir/render/render_view.h"

namespace phyir::cli {

CLI::Option* add_spp_flag(CLI::App* cmd, int& spp);
CLI::Option* add_max_bounces_flag(CLI::App* cmd, int& max_bounces);
CLI::Option* add_light_subpaths_flag(CLI::App* cmd, bool& light_subpaths);
CLI::Option* add_seed_flag(CLI::App* cmd, uint64_t& seed);
CLI::Option* add_threads_flag(CLI::App* cmd, int& threads);

// All five, for a command that renders views: `settings`' spp, bounces, light subpaths and
// seed, and `threads`.
void add_sampling_flags(CLI::App* cmd, render::RenderSettings& settings, int& threads);

}  // namespace phyir::cli
