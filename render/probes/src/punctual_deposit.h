#pragma once
// Punctual lights in the probes. Internal to the probe renderer (docs/probes.md, "What a
// texel is").
#include <cstdint>
#include <vector>

#include "phyir/core/image.h"
#include "phyir/render/probe_grid.h"
#include "phyir/render/render_scene.h"

namespace phyir::render {

// A point, spot or directional light has no extent, so no probe direction ever hits it, yet
// its light reaches a probe's origin along one direction. Each light the origin sees is
// added to the texel that direction falls in, as the radiance that spreads its irradiance
// over the texel's solid angle: a probe's sum of L x solid angle then gives the light's
// irradiance back exactly, which is how the network's rendering layer integrates a probe.
// Exact and noise-free (one shadow ray per probe and light, no random numbers), so it is
// added after the texels are estimated and shared. Returns the shadow rays traced.
uint64_t deposit_punctual_lights(const RenderScene& scene, const ProbeLayout& layout,
                                 const std::vector<ProbeSite>& sites, const std::vector<int>& probes, Image* mosaic);

// The texel (row, col) of an h x w probe that direction `d` falls in.
glm::ivec2 probe_texel_of(const glm::vec3& d, int height, int width);

}  // namespace phyir::render
