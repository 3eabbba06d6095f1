#include "bench_probes_exposure.h"

#include "phyir/core/log.h"
#include "phyir/dataset/input_image.h"
#include "phyir/dataset/settings.h"
#include "phyir/render/render_view.h"

namespace phyir::cli {

double view_input_stops(const render::RenderScene& scene, const render::CameraModel& camera, int spp) {
  render::RenderSettings settings;
  settings.spp = spp;
  settings.aovs = false;
  settings.progress = false;
  const render::RenderOutput out = render::render_view(scene, camera, settings);
  const double stops = dataset::choose_input_exposure(out.film.color(), dataset::InputSettings{}, 0).base_stops;
  spdlog::info("the view's input exposure (the dataset's auto exposure at {} spp): {:+.2f} stops", spp, stops);
  return stops;
}

}  // namespace phyir::cli
