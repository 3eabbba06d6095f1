// phyir insert: a glTF object into a panorama view, lit by the view's probes (spatially
// varying), predicted probes, one global probe, a constant or an HDR file, composited by
// differential rendering (docs/insert.md).
#include <tbb/global_control.h>

#include <cmath>
#include <memory>
#include <optional>
#include <string>

#include "command_insert_path.h"
#include "commands.h"
#include "sampling_flags.h"
#include "phyir/core/error.h"
#include <spdlog/spdlog.h>
#include "phyir/insert/insert_object.h"
#include "phyir/scenes/gltf_loader.h"

namespace phyir::cli {

namespace {

struct InsertOptions {
  std::string view;
  std::string object;
  std::string out = "insert-out";
  std::string maps;  // a prediction folder whose maps replace the view's
  std::vector<int> pixel;
  std::vector<int> path_end;  // --path: the last step's pixel
  int steps = 8;
  double yaw_degrees = 0.0;
  int threads = 0;
  insert::InsertRequest request;
};

scenes::Scene load_object(const std::string& path) {
  try {
    return scenes::load_gltf(path);
  } catch (const Error& e) {
    fail("{}: the object does not load: {}", path, e.what());
  }
}

void run(const InsertOptions& o) {
  std::optional<tbb::global_control> limit;
  if (o.threads > 0) limit.emplace(tbb::global_control::max_allowed_parallelism, size_t(o.threads));
  insert::InsertRequest request = o.request;
  request.x = o.pixel.at(0);
  request.y = o.pixel.at(1);
  request.placement.yaw = float(o.yaw_degrees * M_PI / 180.0);
  if (!(request.placement.scale >= 0.0f)) fail("--scale {}: must be 0 or more", request.placement.scale);
  if (request.lighting.source == "predicted" && request.lighting.predicted_dir.empty())
    fail("--lighting predicted needs --predicted DIR (a `phyir infer` folder)");
  const insert::InsertView view = insert::read_insert_view(o.view, o.maps);
  const scenes::Scene object = load_object(o.object);
  if (!o.path_end.empty()) {
    insert_along_path(view, object, request, {request.x, request.y}, {o.path_end.at(0), o.path_end.at(1)}, o.steps,
                      o.out);
    return;
  }
  const insert::InsertResult result = insert::insert_object(view, object, request);
  insert::write_insert_outputs(o.out, view, result);
  spdlog::info("insert: {} into {} at pixel ({}, {}), lighting {}: {}/composite.png ({:.1f} s)", o.object, o.view,
            request.x, request.y, request.lighting.source, o.out,
            result.record["timings"]["total_seconds"].get<double>());
}

}  // namespace

void add_insert_command(CLI::App& app) {
  auto o = std::make_shared<InsertOptions>();
  auto* cmd = app.add_subcommand("insert", "Insert a glTF object into a panorama view (differential rendering)");
  cmd->add_option("view", o->view, "view folder (dataset view or `phyir render --out` folder)")
      ->required()
      ->check(CLI::ExistingDirectory);
  cmd->add_option("object", o->object, "glTF/GLB object, in metres, +Y up")->required();
  cmd->add_option("--pixel", o->pixel, "X Y: the panorama pixel the object stands on")->required()->expected(2);
  cmd->add_option("--path", o->path_end, "X Y: move the object from --pixel to this pixel (dynamic insertion): frame_NNN/ per step, contact_sheet.png, path.gif")
      ->expected(2);
  cmd->add_option("--steps", o->steps, "frames along --path")->capture_default_str();
  cmd->add_option("--scale", o->request.placement.scale, "uniform scale of the object")->capture_default_str();
  cmd->add_option("--yaw", o->yaw_degrees, "rotation about +Y, degrees")->capture_default_str();
  cmd->add_option("--lighting", o->request.lighting.source,
                  "gt (the view's probes, spatially varying), predicted, global (the probe nearest the pixel), "
                  "constant (mean of the probes) or an HDR environment file")
      ->capture_default_str();
  cmd->add_option("--predicted", o->request.lighting.predicted_dir,
                  "`phyir infer` folder: its probes for --lighting predicted");
  cmd->add_option("--maps", o->maps, "folder whose depth/normal/material maps replace the view's (`phyir infer`)");
  cmd->add_option("--out", o->out, "output folder")->capture_default_str();
  add_spp_flag(cmd, o->request.spp);
  add_max_bounces_flag(cmd, o->request.max_bounces);
  add_seed_flag(cmd, o->request.seed);
  add_threads_flag(cmd, o->threads);
  cmd->callback([o] { run(*o); });
}

}  // namespace phyir::cli
