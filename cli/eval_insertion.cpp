#include "eval_insertion.h"

#include <fmt/format.h>

#include <map>

#include "phyir/core/error.h"
#include "phyir/core/progress.h"
#include "phyir/dataset/checksum.h"
#include "phyir/insert/insert_bench.h"
#include "phyir/render/render_job.h"
#include "phyir/scenes/gltf_loader.h"
#include "phyir/view/view_files.h"

namespace phyir::cli {

namespace fs = std::filesystem;

namespace {

const std::vector<std::string> kLightings = {"predicted", "gt", "global", "constant"};

// The view's scene file (checked against the manifest's checksum by SceneRooms).
fs::path view_scene(const EvalInsertionOptions& o, const view::ViewRecord& v, const nlohmann::json& manifest) {
  const nlohmann::json& scene = v.json.at("scene");
  const std::string file = scene.at("file").get<std::string>();
  const fs::path dir = o.scenes.empty() ? fs::path(manifest.at("scenes_dir").get<std::string>()) : o.scenes;
  fs::path path = dir / file;
  if (!fs::is_regular_file(path) && path.is_relative() && fs::is_regular_file(o.gt_dir / path)) path = o.gt_dir / path;
  if (!fs::is_regular_file(path))
    fail("view {}: its scene {} is not at {} (the manifest's scenes_dir as given to phyir dataset generate; "
         "give the scenes folder with --insertion-scenes)", v.id, file, path.string());
  return path;
}

double mean(const std::vector<double>& v) { return insert::summarize(v).mean; }

// The scenes the views were rendered from, each hashed and loaded once (a scene has several
// views). Each view's record must name the scene by its SHA-256: the truth must be rendered from
// the scene the view was.
struct SceneRooms {
  std::map<fs::path, std::string> hashes;
  std::map<fs::path, insert::BenchRoom> rooms;  // a map's elements stay where they are
  const insert::BenchRoom& at(const fs::path& path, const view::ViewRecord& v) {
    auto& hash = hashes[path];
    if (hash.empty()) hash = dataset::sha256_file(path);
    const std::string expected = v.json.at("scene").value("sha256", "");
    if (!expected.empty() && hash != expected)
      fail("view {}: {} is not the scene the view was rendered from (its SHA-256 differs from the manifest's)", v.id,
           path.string());
    auto it = rooms.find(path);
    if (it == rooms.end()) {
      it = rooms.emplace(path, insert::BenchRoom{scenes::load_gltf(path), nullptr}).first;
      it->second.environment = render::scene_environment(it->second.scene);
    }
    return it->second;
  }
};

std::string markdown(const std::map<std::string, std::map<std::string, std::vector<double>>>& rmse,
                     const std::map<std::string, std::map<std::string, std::vector<double>>>& ssim, int views,
                     size_t cases) {
  std::string t = fmt::format(
      "## Object insertion\n\nTable 10's spheres inserted into the split's first {} view(s) ({} cases: views x placements "
      "x spheres) by differential rendering under each lighting and scored against the scene path traced with the "
      "sphere in it (docs/insert.md): mean RMSE in linear HDR over the sphere and its shadow region (lower is "
      "better) and mean SSIM of the display images (higher is better).\n\n| object |",
      views, cases);
  std::string rule = "| --- |";
  for (const std::string& l : kLightings) t += fmt::format(" RMSE {} |", l), rule += " --- |";
  for (const std::string& l : kLightings) t += fmt::format(" SSIM {} |", l), rule += " --- |";
  t += "\n" + rule + "\n";
  for (const auto& [object, per_lighting] : rmse) {
    t += fmt::format("| {} |", object);
    for (const std::string& l : kLightings) t += fmt::format(" {:.4f} |", mean(per_lighting.at(l)));
    for (const std::string& l : kLightings) t += fmt::format(" {:.3f} |", mean(ssim.at(object).at(l)));
    t += "\n";
  }
  return t;
}

}  // namespace

eval::ReportSection evaluate_insertion(const EvalInsertionOptions& o) {
  const nlohmann::json manifest = view::read_manifest_document(o.gt_dir);
  std::vector<view::ViewRecord> views = eval::split_views(o.gt_dir, o.split);
  if (views.size() > size_t(o.views)) views.resize(size_t(o.views));
  const std::vector<insert::BenchObject> spheres = insert::table10_spheres(o.sphere_radius);
  const float half_width = o.sphere_radius, height = 2.0f * o.sphere_radius;
  insert::BenchSettings settings;
  settings.lightings = kLightings;
  settings.spp = o.spp, settings.truth_spp = o.truth_spp, settings.seeds = o.seeds;
  nlohmann::json cases = nlohmann::json::array(), skipped = nlohmann::json::array();
  std::map<std::string, std::map<std::string, std::vector<double>>> rmse, ssim;  // object -> lighting -> cases
  Progress progress("eval: insertion", views.size(), "views", o.progress);
  SceneRooms rooms;
  for (const view::ViewRecord& v : views) {
    const insert::BenchRoom& room = rooms.at(view_scene(o, v, manifest), v);
    const insert::InsertView iv = insert::read_insert_view(v.dir);
    settings.predicted_dir = o.pred_dir / v.id;
    if (!fs::is_regular_file(settings.predicted_dir / view::kProbesFile))
      fail("view {}: {} is missing (the method's predicted probes)", v.id, (settings.predicted_dir / view::kProbesFile).string());
    std::vector<std::string> missing;
    for (const insert::BenchPlacement& p : insert::find_placements(iv, room.scene, half_width, height, missing)) {
      for (const insert::BenchObject& sphere : spheres) {
        const insert::CaseScores c =
            insert::run_case(iv, room, p, sphere, settings, o.out_dir / "insertion" / v.id / p.name / sphere.name);
        nlohmann::json record = insert::case_record(c, p);
        record["view"] = v.id;
        cases.push_back(record);
        for (const std::string& l : kLightings) {
          rmse[sphere.name][l].push_back(mean(c.rmse.at(l)));
          ssim[sphere.name][l].push_back(mean(c.ssim.at(l)));
        }
      }
    }
    for (const std::string& s : missing) skipped.push_back(v.id + ": " + s);
    progress.advance();
  }
  nlohmann::json means;
  for (const auto& [object, per_lighting] : rmse)
    for (const std::string& l : kLightings)
      means[object][l] = {{"rmse", mean(per_lighting.at(l))}, {"ssim", mean(ssim.at(object).at(l))}};
  nlohmann::json data = {{"views", views.size()}, {"spp", o.spp}, {"truth_spp", o.truth_spp}, {"seeds", o.seeds},
                         {"sphere_radius", o.sphere_radius}, {"lightings", kLightings}, {"mean", means},
                         {"cases", cases}, {"skipped_placements", skipped}};
  return {"insertion", data, markdown(rmse, ssim, int(views.size()), cases.size())};
}

}  // namespace phyir::cli
