#pragma once
// Training-time augmentation of one view at the network's resolutions (docs/model.md
// "Augmentation"): a yaw rotation (a circular shift of every map, the world-space normals
// rotated about +Y, the world-aligned probes moved with their pixels and their texels shifted
// the same way), a horizontal mirror (x -> -x: normals and probes mirrored too) and an
// exposure jitter (input re-exposed, radiance targets scaled by the same factor). Each is an
// exact transform of the tensors (no resampling). Private header (torch types).
#include <cstddef>
#include <cstdint>
#include <vector>

#include "data.h"
#include "exposure.h"
#include "phyir/model/training.h"

namespace phyir::model {

struct AugmentDraw {
  int yaw_steps = 0;        // rotation by yaw_steps / yaw_divisions of a turn, u growing
  bool mirror = false;      // applied after the rotation
  double exposure_stops = 0.0;
};

// The exact rotations: gcd of the input width, the rendering width and the probe width. A
// rotation by k / n of a turn shifts every map and every probe's texels by whole columns
// (input 256, render 64, probes 16 wide: n = 16, steps of 22.5 degrees).
int yaw_divisions(const ModelConfig& config);

// The draw of view `view` in epoch `epoch`: a function of (seed, epoch, view) only, so it
// does not depend on the batch, the thread count or a resume. All three parts are drawn
// whatever the options, so turning one off leaves the others' draws as they were.
AugmentDraw draw_augment(const AugmentOptions& options, int divisions, uint64_t seed, int epoch, size_t view);

// World-space vectors [3, H, W] rotated about +Y so that their azimuth u grows by `turns`
// (x' = x cos a - z sin a, z' = x sin a + z cos a, a = 2 pi turns; docs/conventions.md: u grows
// towards +X from the -Z centre).
torch::Tensor rotate_about_y(const torch::Tensor& vectors, double turns);

// The view seen after turning the world by steps / divisions of a turn (u += steps / divisions).
ViewTensors rotate_view(const ViewTensors& view, int steps, int divisions);
// The view of the world mirrored in x (column j -> W-1-j, u -> 1-u).
ViewTensors mirror_view(const ViewTensors& view);
// The view written at 2^stops times its exposure (exposure.h's reexpose_ldr); targets in input
// units scaled by the same factor, absolute ones unchanged (the scene's radiance is the same).
ViewTensors expose_view(const ViewTensors& view, double stops, view::RadianceUnits units = view::RadianceUnits::kInput);

ViewTensors augment_view(const ViewTensors& view, const AugmentDraw& draw, int divisions,
                         view::RadianceUnits units = view::RadianceUnits::kInput);

// View number `index` of the dataset as training sees it in `epoch`: augmented by its draw
// (as loaded when options.enabled is false); `units`: the targets' unit. The streaming reader
// (view_stream.h) calls it on each view it decodes.
ViewTensors augment_for_epoch(const ViewTensors& view, size_t index, const AugmentOptions& options, int divisions,
                              uint64_t seed, int epoch, view::RadianceUnits units = view::RadianceUnits::kInput);

// The batch of views[indices] in `epoch`, each view through augment_for_epoch, then collate
// (views held in memory: the reference the stream is tested against, and tests).
Batch augmented_batch(const std::vector<ViewTensors>& views, const std::vector<size_t>& indices,
                      const AugmentOptions& options, int divisions, uint64_t seed, int epoch,
                      view::RadianceUnits units = view::RadianceUnits::kInput);

}  // namespace phyir::model
