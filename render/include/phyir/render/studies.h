#pragma once
// What accuracy costs in time: the measurements behind `phyir bench`. Each returns plain
// numbers; the command writes them as CSV and plots them.
#include <vector>

#include "phyir/core/image.h"
#include "phyir/render/camera.h"
#include "phyir/render/render_view.h"

namespace phyir::render {

struct ConvergencePoint {
  int spp = 0;
  double seconds = 0.0;
  double rmse = 0.0;
  double relative_rmse = 0.0;
  double rays_per_second = 0.0;
};

// Renders `camera` at each spp (colour only, seed differing from the reference's) and
// measures error against `reference`.
std::vector<ConvergencePoint> convergence_study(const RenderScene& scene, const CameraModel& camera,
                                                RenderSettings settings, const std::vector<int>& spp_list,
                                                const Image& reference);

struct EffectsComparison {
  Effects specialised;
  double specialised_seconds = 0.0;
  double forced_seconds = 0.0;
  bool identical = false;  // bit-identical color
};

// The scene's specialised kernel against every effect forced on; best of `repeats` runs.
EffectsComparison compare_effect_kernels(const RenderScene& scene, const CameraModel& camera,
                                         const RenderSettings& settings, int repeats);

struct ThroughputReport {
  double integrator_rays_per_second = 0.0;   // all rays of a full render / its time
  double embree_single_rays_per_second = 0.0;  // the replayed rays, rtcIntersect1 one by one
  double embree_packet_rays_per_second = 0.0;  // the replayed rays, rtcIntersect16 packets
  size_t replayed_rays = 0;
};

// Integrator throughput versus raw Embree on rays of the same scene: camera rays plus
// cosine-distributed bounce rays from their hits (the integrator's ray population).
ThroughputReport measure_throughput(const RenderScene& scene, const CameraModel& camera,
                                    const RenderSettings& settings);

}  // namespace phyir::render
