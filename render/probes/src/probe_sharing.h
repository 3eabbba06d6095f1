#pragma once
// Sharing samples between neighbouring probes of one surface (cache mode; docs/probes-estimator.md,
// "Sharing between neighbours").
//
// Probes of adjacent grid cells on one surface are centimetres apart, and a texel whose
// content is metres away sees nearly the same radiance from both. So each texel of a valid
// probe is averaged with the same texel of the valid probes in the (2r+1) x (2r+1) window of
// the grid around it, weighted by their sample counts, where
//  - the two probes lie on one surface: normals within ~25 degrees, each origin within a
//    tenth of their distance (plus 2 mm) of the other's tangent plane, at most max_baseline
//    apart;
//  - the texel's parallax is small: the part of the baseline across the texel's centre
//    direction is below parallax_texels times the texel's smaller extent (its height pi/h,
//    or its width at its centre row near the poles) seen from the nearer of the two
//    probes' hit distances in that texel, and those distances agree within a factor of 2
//    (else one probe sees an occluder the other does not);
//  - the two values agree within kConsistentErrors (3) standard errors of their difference,
//    from each texel's variance: a halo or an edge moved across one of them by parallax
//    differs by more than its noise, and averaging would blur it. A supersampled texel's
//    variance comes from its strata's differences (stratified_mean_variance), which do not
//    count an edge its strata resolve; the spread of its directions would, and let a
//    window's sill moved by parallax pass for noise.
// The window's probes draw interleaved strata (sub_stratum), so their average is a
// stratified estimate over (2r+1)^2 times as many strata as one probe's.
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

// What shading records per texel (index probe * texels_per_probe + texel): the nearest hit
// distance among its directions (infinity where all missed), its sample count and the
// variance of its value's luminance (from its strata's differences where it has enough of
// them, else its directions' sample variance over their count).
struct TexelRecords {
  std::vector<float> distance;
  std::vector<float> samples;
  std::vector<float> variance;  // of its value's luminance
};

// The mosaic with each valid computed probe's texels averaged over its neighbours as above.
// `computed` flags the probes whose texels and records are filled. Returns the number of
// texels that took in at least one neighbour in *shared_texels, and, if `standard_error`
// (one channel, the mosaic's size) is given, writes each shared texel's standard error there:
// sqrt(sum n^2 variance) / sum n over the texels averaged.
Image share_between_neighbours(const Image& mosaic, const ProbeLayout& layout, const std::vector<ProbeSite>& sites,
                               const std::vector<uint8_t>& computed, const TexelRecords& records,
                               const ProbeSharing& sharing, uint64_t* shared_texels,
                               Image* standard_error = nullptr);

}  // namespace phyir::render
