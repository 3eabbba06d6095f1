#pragma once
// The unit `phyir eval --radiance input` scores in, for `phyir bench probes`' lighting metrics:
// radiance times 2^stops, stops the auto exposure `phyir dataset` gives the view's input
// image (docs/eval.md "Radiance units"). Absolute errors follow the scene's brightness (a
// night room's are tiny whatever its relative error); in input units every view has its
// input image's scale, the unit the network is trained and compared in.
#include "phyir/render/camera.h"
#include "phyir/render/render_scene.h"

namespace phyir::cli {

// The dataset's default auto exposure (dataset::choose_input_exposure, no jitter) of the view
// `camera` sees, rendered at `spp` (its 95th percentile needs few samples).
double view_input_stops(const render::RenderScene& scene, const render::CameraModel& camera, int spp);

}  // namespace phyir::cli
