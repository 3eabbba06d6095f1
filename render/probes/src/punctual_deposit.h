#pragma once
// Punctual lights in the probes (docs/probes.md, "What a texel is"). Internal.
#include <cstdint>
#include <vector>

#include "phyir/core/image.h"
#include "phyir/render/probe_grid.h"
#include "phyir/render/render_scene.h"

namespace phyir::render {

// Adds each punctual light a probe's origin sees to the texel its direction falls in, as the
// radiance spreading its irradiance over the texel (sum of L x solid angle gives it exactly);
// noise-free, so added after estimating and sharing. Returns the shadow rays (one per light).
uint64_t deposit_punctual_lights(const RenderScene& scene, const ProbeLayout& layout,
                                 const std::vector<ProbeSite>& sites, const std::vector<int>& probes, Image* mosaic);

// The texel (row, col) of an h x w probe that direction `d` falls in.
glm::ivec2 probe_texel_of(const glm::vec3& d, int height, int width);

}  // namespace phyir::render
