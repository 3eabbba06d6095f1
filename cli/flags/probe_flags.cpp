#include "probe_flags.h"

#include <fmt/format.h>

#include "flag_registry.h"
#include "phyir/render/probe_grid.h"

namespace phyir::cli {

namespace {

constexpr const char* kGroup = "Light probes";

// Registers the group's options on one command: each under its name (and its second name).
struct ProbeFlagAdder {
  CLI::App* cmd;
  const std::map<std::string, std::string>& also_named;

  std::string names(const std::string& flag) const {
    const auto other = also_named.find(flag);
    return other == also_named.end() ? flag : flag + "," + other->second;
  }
  template <class T>
  void option(const std::string& setting, const std::string& flag, T& field, const std::string& help) const {
    sets(cmd, setting, cmd->add_option(names(flag), field, help))->capture_default_str()->group(kGroup);
  }
  // "HxW" into two fields.
  void size(const std::string& setting, const std::string& flag, int& height, int& width, const std::string& help) const {
    sets(cmd, setting,
         cmd->add_option_function<std::string>(
             names(flag), [flag, &height, &width](const std::string& text) { view::parse_size(text, flag, &height, &width); },
             help))
        ->default_str(fmt::format("{}x{}", height, width))
        ->group(kGroup);
  }
};

void add_sampling(const ProbeFlagAdder& add, render::ProbeSettings& probe) {
  add.option("probe.spp", "--probe-spp", probe.spp, "directions per probe texel");
  sets(add.cmd, "probe.mode",
       add.cmd->add_option_function<std::string>(
           add.names("--probe-mode"), [&probe](const std::string& name) { probe.mode = render::parse_probe_mode(name); },
           "cache (shared irradiance cache) or path (unbiased reference, slow)"))
      ->default_str(render::probe_mode_name(probe.mode))
      ->group(kGroup);
  add.option("probe.target_error", "--probe-error", probe.target_error,
             "render again where the noise is until the grid's estimated relative error (from each texel's standard "
             "error, probe_stderr.exr) is at most this, e.g. 0.05 (0: one pass)");
  sets(add.cmd, "probe.progressive",
       add.cmd->add_flag_callback(
           "--no-probe-progressive", [&probe] { probe.progressive = false; },
           "with --probe-error: every pass with the first's cache cells and sharing bound (by default later passes shrink "
           "them, so that the passes' mean is consistent)"))
      ->group(kGroup);
}

void add_cache(const ProbeFlagAdder& add, render::ProbeSettings& probe) {
  add.option("probe.cache.cell_size", "--probe-cache-cell", probe.cache.cell_size, "cache mode: cell size, metres");
  add.option("probe.cache.samples_per_cell", "--probe-cache-spp", probe.cache.samples_per_cell,
             "cache mode: irradiance samples per cell");
  add.option("probe.cache.direct_distance_cells", "--probe-cache-direct-cells", probe.cache.direct_distance_cells,
             "cache mode: cache direct light too in cells at least this many cell sizes from every emitter (0: never)");
  add.option("probe.spread_threshold", "--probe-spread-threshold", probe.spread_threshold,
             fmt::format("cache mode: a texel whose first samples spread over more than this times their mean gets "
                         "{}x the samples (hard-texel sampling)",
                         probe.hard_spp_factor));
  add.option("probe.sharing.radius", "--probe-share-radius", probe.sharing.radius,
             "cache mode: average each texel with the probes up to this many grid cells away on the same surface "
             "where parallax is small (0: off)");
  add.option("probe.sharing.parallax_texels", "--probe-share-parallax", probe.sharing.parallax_texels,
             "cache mode: largest parallax between shared probes, in texel heights");
}

}  // namespace

void add_probe_flags(CLI::App* cmd, render::ProbeSettings& probe, unsigned which,
                     const std::map<std::string, std::string>& also_named) {
  const ProbeFlagAdder add{cmd, also_named};
  render::ProbeLayout& layout = probe.layout;
  if (which & kProbeGrid)
    add.size("probe.grid", "--probe-grid", layout.grid_height, layout.grid_width,
             "probes HxW (the paper: one per 2x2 pixel block of the panorama)");
  if (which & kProbeResolution)
    add.size("probe.res", "--probe-res", layout.res_height, layout.res_width, "texels per probe hxw (equirectangular)");
  if (which & kProbeSampling) add_sampling(add, probe);
  if (which & kProbeOffset)
    add.option("probe.offset", "--probe-offset", probe.offset,
               "probe origin's distance off the surface along its normal, metres");
  if (which & kProbeCache) add_cache(add, probe);
  if (which & kProbePhotons)
    add.option("probe.photons_per_light", "--probe-photons", probe.photons_per_light,
               "cache mode: photons from each point and spot light, and per square metre of the sun's beam where it "
               "reaches the probes, which take the light they reflect where they land densely (0: none)");
  if (which & kProbeBalance)
    add.option("probe.balance", "--probe-balance", probe.balance,
               "cache mode: extra directions for each probe's noisiest texels, as a fraction of those its texels "
               "took, shared out by each texel's noise per direction (0: none)");
  if (which & kProbePunctual)
    cmd->add_flag_callback(
           "--no-probe-punctual-lights", [&probe] { probe.punctual_lights = false; },
           "leave the punctual lights out of the probes (to measure what they add; docs/probes.md)")
        ->group(kGroup);
}

}  // namespace phyir::cli
