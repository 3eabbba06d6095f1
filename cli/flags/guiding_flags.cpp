#include "guiding_flags.h"

#include "flag_registry.h"

namespace phyir::cli {

namespace {
constexpr const char* kGroup = "Path guiding";
}  // namespace

void add_guiding_flags(CLI::App* cmd, render::GuidingSettings& guiding) {
  sets(cmd, "guiding.enabled",
       cmd->add_flag("--guiding", guiding.enabled,
                     "learn where the light comes from (an SD-tree, trained in passes of 1, 2, 4, ... spp) and "
                     "sample paths towards it; same total --spp, a \"guiding\" block in render.json"))
      ->group(kGroup);
  sets(cmd, "guiding.bsdf_fraction",
       cmd->add_option("--guiding-bsdf-fraction", guiding.bsdf_fraction,
                       "share of directions drawn from the BRDF rather than the guide, in (0, 1]"))
      ->capture_default_str()
      ->group(kGroup);
  sets(cmd, "guiding.spatial_threshold",
       cmd->add_option("--guiding-spatial-threshold", guiding.tree.spatial_threshold,
                       "records a spatial cell takes before it splits (c of c sqrt(2^pass))"))
      ->capture_default_str()
      ->group(kGroup);
}

}  // namespace phyir::cli
