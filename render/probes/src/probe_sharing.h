#pragma once
// Sharing samples between neighbouring probes of one surface (cache mode): which texels are
// averaged, and the interleaved strata that make the average stratified, are
// docs/probes-estimator.md, "Sharing between neighbours".
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "phyir/core/image.h"
#include "phyir/render/probe_grid.h"
#include "phyir/render/probe_settings.h"

namespace phyir::render {

// Which of the window() x window() sub-cells of its strata probe (i, j) draws from: (j mod
// n, i mod n), so any full window of the grid holds each sub-cell once.
glm::ivec2 sub_stratum(int i, int j, const ProbeSharing& sharing);

// What shading records per texel (index probe * texels_per_probe + texel): its nearest hit
// distance (infinity where all missed), its sample count and its value's luminance variance,
// from its own samples and from the cache's fill noise.
struct TexelRecords {
  std::vector<float> distance;
  std::vector<float> samples;
  std::vector<float> variance;        // of its value's luminance, its own samples' part
  std::vector<float> cache_variance;  // the cache's part (empty: none)
};

// The mosaic with each valid computed probe's texels averaged over its neighbours (`computed`:
// the probes whose texels and records are filled). *shared_texels: the texels that took in a
// neighbour; `standard_error` (1 channel, mosaic-sized) gets theirs: the own parts independent,
// sum n^2 var / (sum n)^2, the cache's as one error read by all, (sum n sigma_cache / sum n)^2.
Image share_between_neighbours(const Image& mosaic, const ProbeLayout& layout, const std::vector<ProbeSite>& sites,
                               const std::vector<uint8_t>& computed, const TexelRecords& records,
                               const ProbeSharing& sharing, uint64_t* shared_texels,
                               Image* standard_error = nullptr);

}  // namespace phyir::render
