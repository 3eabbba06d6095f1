#include "phyir/render/studies.h"

#include <tbb/parallel_for.h>

#include "phyir/core/image_error.h"
#include "phyir/core/stopwatch.h"
#include "phyir/render/frame.h"
#include "phyir/render/ray_offset.h"
#include "phyir/render/rng.h"
#include "phyir/render/sampling.h"

namespace phyir::render {

namespace {

// Camera rays through random pixel positions plus up to 4 cosine bounces from each hit.
std::vector<Ray> replay_rays(const RenderScene& scene, const CameraModel& camera, size_t paths) {
  std::vector<Ray> rays;
  rays.reserve(paths * 3);
  Rng rng(12345, 7);
  for (size_t i = 0; i < paths; ++i) {
    Ray ray = camera.generate_ray(rng.next_2d() * glm::vec2(camera.width, camera.height));
    for (int bounce = 0; bounce < 5; ++bounce) {
      rays.push_back(ray);
      SurfaceInteraction si;
      if (!scene.trace(ray, &si)) break;
      const Frame frame(si.geometric_normal);
      const glm::vec3 wi = frame.to_world(sample_cosine_hemisphere(rng.next_2d()));
      ray = Ray{spawn_origin(si.position, si.geometric_normal, wi), wi};
    }
  }
  return rays;
}

}  // namespace

std::vector<ConvergencePoint> convergence_study(const RenderScene& scene, const CameraModel& camera,
                                                RenderSettings settings, const std::vector<int>& spp_list,
                                                const Image& reference) {
  std::vector<ConvergencePoint> points;
  settings.aovs = false;
  settings.progress = false;
  settings.seed += 1;  // independent of the reference's samples
  for (int spp : spp_list) {
    settings.spp = spp;
    const RenderOutput out = render_view(scene, camera, settings);
    const ImageError e = image_error(out.film.color(), reference);
    ConvergencePoint p;
    p.spp = spp;
    p.seconds = out.stats.color_seconds;
    p.rmse = e.rmse;
    p.relative_rmse = e.relative_rmse;
    p.rays_per_second = out.stats.counters.rays / std::max(out.stats.color_seconds, 1e-9);
    points.push_back(p);
  }
  return points;
}

EffectsComparison compare_effect_kernels(const RenderScene& scene, const CameraModel& camera,
                                         const RenderSettings& settings, int repeats) {
  EffectsComparison result;
  RenderSettings s = settings;
  s.aovs = false;
  s.progress = false;
  result.specialised_seconds = result.forced_seconds = 1e30;
  Image specialised, forced;
  for (int r = 0; r < repeats; ++r) {
    s.force_all_effects = false;
    RenderOutput a = render_view(scene, camera, s);
    result.specialised = a.effects;
    result.specialised_seconds = std::min(result.specialised_seconds, a.stats.color_seconds);
    specialised = a.film.color();
    s.force_all_effects = true;
    RenderOutput b = render_view(scene, camera, s);
    result.forced_seconds = std::min(result.forced_seconds, b.stats.color_seconds);
    forced = b.film.color();
  }
  result.identical = specialised.pixels == forced.pixels;
  return result;
}

ThroughputReport measure_throughput(const RenderScene& scene, const CameraModel& camera,
                                    const RenderSettings& settings) {
  ThroughputReport report;
  RenderSettings s = settings;
  s.aovs = false;
  s.progress = false;
  const RenderOutput out = render_view(scene, camera, s);
  report.integrator_rays_per_second = out.stats.counters.rays / std::max(out.stats.color_seconds, 1e-9);

  const std::vector<Ray> rays = replay_rays(scene, camera, 200000);
  report.replayed_rays = rays.size();
  const Accelerator& accel = scene.accelerator();
  std::vector<float> t(rays.size());
  const Stopwatch single_watch;
  tbb::parallel_for(tbb::blocked_range<size_t>(0, rays.size(), 4096), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t i = r.begin(); i < r.end(); ++i) {
      Hit hit;
      t[i] = accel.intersect(rays[i], &hit) ? hit.t : -1.0f;
    }
  });
  report.embree_single_rays_per_second = rays.size() / std::max(single_watch.seconds(), 1e-9);
  const Stopwatch packet_watch;
  tbb::parallel_for(tbb::blocked_range<size_t>(0, rays.size(), 4096), [&](const tbb::blocked_range<size_t>& r) {
    accel.intersect_batch(rays.data() + r.begin(), r.size(), t.data() + r.begin());
  });
  report.embree_packet_rays_per_second = rays.size() / std::max(packet_watch.seconds(), 1e-9);
  return report;
}

}  // namespace phyir::render
