#include "sampling_flags.h"

#include "flag_registry.h"

namespace phyir::cli {

namespace {
constexpr const char* kGroup = "Sampling";
}  // namespace

CLI::Option* add_spp_flag(CLI::App* cmd, int& spp) {
  return sets(cmd, "spp", cmd->add_option("--spp", spp, "paths per pixel"))->capture_default_str()->group(kGroup);
}

CLI::Option* add_max_bounces_flag(CLI::App* cmd, int& max_bounces) {
  return sets(cmd, "max_bounces", cmd->add_option("--max-bounces", max_bounces, "scattering events after the first hit"))
      ->capture_default_str()
      ->group(kGroup);
}

CLI::Option* add_seed_flag(CLI::App* cmd, uint64_t& seed) {
  return sets(cmd, "seed", cmd->add_option("--seed", seed, "random seed (same seed, same output)"))
      ->capture_default_str()
      ->group(kGroup);
}

CLI::Option* add_threads_flag(CLI::App* cmd, int& threads) {
  return sets(cmd, "threads",
              cmd->add_option("--threads", threads, "worker threads (0 = all cores); never changes the output"))
      ->capture_default_str()
      ->group(kGroup);
}

CLI::Option* add_light_subpaths_flag(CLI::App* cmd, bool& light_subpaths) {
  return sets(cmd, "light_subpaths",
              cmd->add_option("--light-subpaths", light_subpaths,
                              "join a path from a point or spot light at every vertex (docs/light-subpaths.md; scenes with such lights): "
                              "the light a bulb throws on surfaces close to it, at one more ray per path and per vertex"))
      ->capture_default_str()
      ->group(kGroup);
}

void add_sampling_flags(CLI::App* cmd, render::RenderSettings& settings, int& threads) {
  add_spp_flag(cmd, settings.spp);
  add_max_bounces_flag(cmd, settings.path.max_bounces);
  add_light_subpaths_flag(cmd, settings.path.light_subpaths);
  add_seed_flag(cmd, settings.seed);
  add_threads_flag(cmd, threads);
}

}  // namespace phyir::cli
