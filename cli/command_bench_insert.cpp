// phyir bench insert: object insertion scored against the truth. On a rendered view of a scene
// we have, the object is rendered into the scene itself by the path tracer (full global
// illumination, same camera), and the composites made under the view's probes (spatially
// varying), one global probe and a constant environment are scored against it over several
// seeds (bench_insert.h): RMSE and SSIM per placement, object and lighting, and the temporal
// consistency of the object's shading along a floor path.
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <memory>
#include <string>
#include <vector>

#include "commands.h"
#include "phyir/core/atomic_file.h"
#include "phyir/core/error.h"
#include "phyir/core/machine.h"
#include "phyir/insert/insert_bench.h"
#include "phyir/render/render_job.h"
#include "phyir/scenes/asset_gltf.h"
#include "phyir/scenes/asset_library.h"
#include "phyir/scenes/gltf_loader.h"

namespace phyir::cli {

namespace fs = std::filesystem;

namespace {

using insert::BenchObject;
using insert::BenchPlacement;

struct BenchInsertOptions {
  std::string view, scene, out = "bench-insert";
  std::vector<std::string> objects;   // extra glTF objects besides the spheres
  std::vector<std::string> assets;    // furniture library ids, converted to glTF
  std::string assets_dir;             // the library (empty: the toolkit's default)
  float asset_height = 0.3f;          // metres: library pieces are scaled to this height
  std::vector<std::string> only_placements, only_objects;  // empty: all
  float sphere_radius = 0.15f;
  insert::BenchSettings bench;
};

bool listed(const std::vector<std::string>& names, const std::string& name) {
  return std::find(names.begin(), names.end(), name) != names.end();
}

// Letters and digits of a library id, for a file name ("Scopia#desk_lamp1" -> "Scopia_desk_lamp1").
std::string file_stem(const std::string& id) {
  std::string s = id;
  for (char& c : s)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return s;
}

// A furniture library piece as a glTF object (written to out/objects/), `height` metres tall.
BenchObject asset_object(const scenes::AssetLibrary& library, const std::string& id, float height, const fs::path& out) {
  const scenes::AssetEntry& entry = library.at(id);
  const fs::path gltf = out / "objects" / (file_stem(id) + ".gltf");
  fs::create_directories(gltf.parent_path());
  scenes::write_asset_gltf(gltf, entry, scenes::load_model(entry));
  scenes::Scene s = scenes::load_gltf(gltf);
  const scenes::Bounds b = s.compute_bounds();
  const float scale = height / std::max(b.max.y - b.min.y, 1e-6f);
  for (scenes::Mesh& m : s.meshes)
    for (glm::vec3& p : m.positions) p *= scale;
  s.bounds = s.compute_bounds();
  return {file_stem(id), std::move(s)};
}

std::vector<BenchObject> bench_objects(const BenchInsertOptions& o) {
  std::vector<BenchObject> objects = insert::table10_spheres(o.sphere_radius);
  for (const std::string& f : o.objects) objects.push_back({fs::path(f).stem().string(), scenes::load_gltf(f)});
  if (!o.assets.empty()) {
    const scenes::AssetLibrary library =
        scenes::AssetLibrary::open(o.assets_dir.empty() ? scenes::kDefaultAssetDir : fs::path(o.assets_dir));
    for (const std::string& id : o.assets) objects.push_back(asset_object(library, id, o.asset_height, o.out));
  }
  if (!o.only_objects.empty())
    objects.erase(std::remove_if(objects.begin(), objects.end(), [&](const BenchObject& b) { return !listed(o.only_objects, b.name); }),
                  objects.end());
  if (objects.empty()) fail("bench insert: no object left to score (the object filter matches none)");
  return objects;
}

void run(const BenchInsertOptions& o) {
  if (o.bench.seeds < 1) fail("--seeds {}: at least 1", o.bench.seeds);
  const auto& l = o.bench.lightings;
  if (std::find(l.begin(), l.end(), "predicted") != l.end() && o.bench.predicted_dir.empty())
    fail("bench insert: the predicted lighting needs --predicted DIR (a phyir infer folder for the view)");
  const insert::InsertView v = insert::read_insert_view(o.view);
  insert::BenchRoom room{scenes::load_gltf(o.scene), nullptr};
  room.environment = render::scene_environment(room.scene);
  const scenes::Scene& scene = room.scene;
  const std::vector<BenchObject> objects = bench_objects(o);
  float half_width = 0.0f, height = 0.0f;
  for (const BenchObject& b : objects) {
    const scenes::Bounds box = b.scene.compute_bounds();
    half_width = std::max({half_width, 0.5f * (box.max.x - box.min.x), 0.5f * (box.max.z - box.min.z)});
    height = std::max(height, box.max.y - box.min.y);
  }
  std::vector<std::string> skipped;
  std::vector<BenchPlacement> placements = insert::find_placements(v, scene, half_width, height, skipped);
  if (!o.only_placements.empty())
    placements.erase(std::remove_if(placements.begin(), placements.end(),
                                    [&](const BenchPlacement& p) { return !listed(o.only_placements, p.name); }),
                     placements.end());
  for (const std::string& s : skipped) spdlog::info("bench insert: no placement {}", s);
  const insert::BenchSettings& b = o.bench;
  nlohmann::json record = {{"view", o.view}, {"scene", o.scene}, {"spp", b.spp}, {"truth_spp", b.truth_spp},
                           {"seeds", b.seeds}, {"lightings", b.lightings}, {"skipped_placements", skipped},
                           {"machine", machine_description()}};
  std::vector<insert::CaseScores> cases;
  for (const BenchPlacement& p : placements)
    for (const BenchObject& object : objects) {
      spdlog::info("bench insert: {} on the {} (pixel {}, {}; {})", object.name, p.name, p.x, p.y, p.note);
      cases.push_back(insert::run_case(v, room, p, object, b, fs::path(o.out) / p.name / object.name));
      record["cases"].push_back(insert::case_record(cases.back(), p));
    }
  std::string md = insert::cases_table(cases, b.lightings);
  for (const std::string& s : skipped) md += fmt::format("\nNo placement {}.\n", s);
  const auto write = [&] {  // after the cases and again after the path: a failed path keeps the cases
    write_file_atomic(fs::path(o.out) / "insert_bench.md", md);
    write_file_atomic(fs::path(o.out) / "insert_bench.json", record.dump(2) + "\n");
  };
  write();
  const auto floor = std::find_if(placements.begin(), placements.end(), [](const BenchPlacement& p) { return p.name == "floor"; });
  if (b.path_steps > 1 && floor != placements.end()) {
    std::vector<insert::PathScores> paths;
    for (const BenchObject& object : objects) {
      paths.push_back(insert::run_path(v, room, *floor, object, b, fs::path(o.out) / "path" / object.name));
      record["paths"].push_back(insert::path_record(paths.back()));
    }
    md += "\n" + insert::path_table(paths, b.lightings);
    write();
  }
  fmt::print("{}", md);
}

}  // namespace

void add_bench_insert_command(CLI::App& bench) {
  auto o = std::make_shared<BenchInsertOptions>();
  auto* cmd = bench.add_subcommand("insert", "object insertion against the scene re-rendered with the object in it");
  cmd->add_option("view", o->view, "view folder rendered with --probes from --scene")
      ->required()
      ->check(CLI::ExistingDirectory);
  cmd->add_option("--scene", o->scene, "the view's glTF scene")->required()->check(CLI::ExistingFile);
  cmd->add_option("--object", o->objects, "an extra glTF object to score besides the three spheres (repeatable)");
  cmd->add_option("--asset", o->assets,
                  "a furniture library id (`phyir assets list`) to score as an object, converted to glTF (repeatable)");
  cmd->add_option("--assets", o->assets_dir, "the furniture library folder or .sh3f (default: Debian's)");
  cmd->add_option("--asset-height", o->asset_height, "metres: library pieces are scaled to this height")
      ->capture_default_str();
  cmd->add_option("--placements", o->only_placements, "only these placements (floor table lamp window)");
  cmd->add_option("--objects", o->only_objects, "only these objects (diffuse matte_silver mirror_silver, file stems, asset ids)");
  cmd->add_option("--lightings", o->bench.lightings, "lighting sources to composite with: gt, gt_plane (only the support plane's probes), gt_p4 (weights 1/r^4), gt_point (distances to the vertex, not the ray), gt_foot (distances between foot points), gt_projected, predicted (with --predicted), global, constant, an HDR file")
      ->capture_default_str();
  cmd->add_option("--predicted", o->bench.predicted_dir,
                  "the prediction folder (`phyir infer` on the view's input.png) the `predicted` lighting reads")
      ->check(CLI::ExistingDirectory);
  cmd->add_option("--out", o->out, "output folder")->capture_default_str();
  cmd->add_option("--spp", o->bench.spp, "paths per pixel of the composites' local renders")->capture_default_str();
  cmd->add_option("--truth-spp", o->bench.truth_spp, "paths per pixel of the true render")->capture_default_str();
  cmd->add_option("--seeds", o->bench.seeds, "seeds per case (1..N): scores are mean ± sd over them")->capture_default_str();
  cmd->add_option("--path-steps", o->bench.path_steps, "frames of the floor path case (0: none)")->capture_default_str();
  cmd->add_option("--path-stride", o->bench.path_stride, "pixels between path frames")->capture_default_str();
  cmd->add_option("--radius", o->sphere_radius, "sphere radius, metres")->capture_default_str();
  cmd->callback([o] { run(*o); });
}

}  // namespace phyir::cli
