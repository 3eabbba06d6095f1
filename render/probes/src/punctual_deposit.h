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

// The irradiance the punctual lights give a point, occlusion included: sum over the lights it
// sees of E max(0, n . wi), n its unit shading normal, lights below its geometric normal `ng`
// left out; one shadow ray per light that faces it (counted in *rays). Exact, no random
// numbers: at a probe's origin, what its texels can never hold of the light its foot gets;
// at a surface, the diffuse light of the punctual lights without the cache's blur.
glm::vec3 punctual_irradiance(const RenderScene& scene, const glm::vec3& position, const glm::vec3& n,
                              const glm::vec3& ng, uint64_t* rays);

// The texel (row, col) of an h x w probe that direction `d` falls in.
glm::ivec2 probe_texel_of(const glm::vec3& d, int height, int width);

}  // namespace phyir::render
