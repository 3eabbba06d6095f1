// phyir bench insert: object insertion scored against the truth. On a rendered view of a scene
// we have, the object is rendered into the scene itself by the path tracer (full global
// illumination, same camera), and the composites made under the view's probes (spatially
// varying), one global probe and a constant environment are scored against it: RMSE in linear
// HDR over the object and its support surface (its shadow region), per material and placement.
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <cmath>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "commands.h"
#include "phyir/core/atomic_file.h"
#include "phyir/core/colour.h"
#include "phyir/core/error.h"
#include "phyir/core/image_io.h"
#include "phyir/core/machine.h"
#include "phyir/eval/relight.h"
#include "phyir/insert/insert_object.h"
#include "phyir/render/render_job.h"
#include "phyir/render/render_view.h"
#include "phyir/scenes/gltf_loader.h"

namespace phyir::cli {

namespace fs = std::filesystem;

namespace {

struct BenchInsertOptions {
  std::string view, scene, object, out = "bench-insert";
  int spp = 64;           // the composites' local renders
  int truth_spp = 512;    // the true render with the object in the scene
  float sphere_radius = 0.15f;
  uint64_t seed = 1;
};

struct NamedPlacement {
  std::string name;
  int x = -1, y = -1;
};

struct BenchObject {
  std::string name;
  scenes::Scene scene;
};

// The relighting sphere of `material` (eval's), `radius`, standing on y = 0.
scenes::Scene sphere_object(const eval::SphereMaterial& material, float radius) {
  scenes::Scene s = eval::material_sphere(material, radius, 64, 32);
  for (glm::vec3& p : s.meshes[0].positions) p.y += radius;
  s.bounds = s.compute_bounds();
  return s;
}

// Whether the 7x7 pixels around (x, y) are all one horizontal surface at one height (not an edge).
bool flat_around(const insert::InsertView& v, int x, int y, float height) {
  for (int dy = -3; dy <= 3; ++dy)
    for (int dx = -3; dx <= 3; ++dx) {
      const int px = (x + dx + v.width()) % v.width(), py = y + dy;
      if (py < 0 || py >= v.height() || !(v.depth.at(px, py) > 0.0f) || v.normal.at(px, py, 1) < 0.95f) return false;
      if (std::abs(insert::surface_at(v, px, py).position.y - height) > 0.01f) return false;
    }
  return true;
}

// The floor pixel nearest 2 m away, and a raised horizontal surface (a table, a box) nearest 1.5 m.
std::vector<NamedPlacement> find_placements(const insert::InsertView& v) {
  float floor_y = 1e30f;
  for (int y = v.height() / 2; y < v.height(); ++y)
    for (int x = 0; x < v.width(); ++x)
      if (v.depth.at(x, y) > 0.0f && v.normal.at(x, y, 1) > 0.95f)
        floor_y = std::min(floor_y, insert::surface_at(v, x, y).position.y);
  NamedPlacement floor{"floor"}, raised{"table"};
  float best_floor = 1e30f, best_raised = 1e30f;
  for (int y = v.height() / 2; y < v.height(); ++y)
    for (int x = 0; x < v.width(); ++x) {
      if (!(v.depth.at(x, y) > 0.0f) || v.normal.at(x, y, 1) < 0.95f) continue;
      const float h = insert::surface_at(v, x, y).position.y, d = v.depth.at(x, y);
      const bool on_floor = h < floor_y + 0.02f, on_raised = h > floor_y + 0.3f && h < v.camera.y - 0.2f;
      const float score = std::abs(d - (on_floor ? 2.0f : 1.5f));
      if (!(on_floor ? score < best_floor : on_raised && score < best_raised) || !flat_around(v, x, y, h)) continue;
      NamedPlacement& p = on_floor ? floor : raised;
      (on_floor ? best_floor : best_raised) = score;
      p.x = x, p.y = y;
    }
  std::vector<NamedPlacement> out;
  for (const NamedPlacement& p : {floor, raised})
    if (p.x >= 0) out.push_back(p);
  if (out.empty()) fail("{}: no horizontal surface to place an object on", v.dir.string());
  return out;
}

// The scene rendered with the object really in it, from the view's camera.
Image true_render(const scenes::Scene& scene, const scenes::Scene& placed, const insert::InsertView& v,
                  const BenchInsertOptions& o) {
  const scenes::Scene both = insert::merge_scenes(scene, placed);
  const render::RenderScene rs(both, render::scene_environment(scene));
  const render::CameraModel camera = insert::panorama_camera(v);
  render::RenderSettings settings;
  settings.spp = o.truth_spp;
  settings.seed = o.seed;
  settings.aovs = false;
  settings.progress = false;
  return render::render_view(rs, camera, settings).film.color();
}

// RMSE over the pixels where `region` is set, three channels.
double masked_rmse(const Image& a, const Image& b, const Image& region) {
  double sum = 0.0;
  size_t n = 0;
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x) {
      if (region.at(x, y) < 0.5f) continue;
      for (int c = 0; c < 3; ++c) sum += std::pow(double(a.at(x, y, c)) - double(b.at(x, y, c)), 2.0);
      n += 3;
    }
  return n ? std::sqrt(sum / double(n)) : 0.0;
}

struct CaseResult {
  std::string placement, object;
  std::vector<std::pair<std::string, double>> rmse;  // per lighting
  double truth_seconds = 0.0;
};

CaseResult run_case(const insert::InsertView& v, const scenes::Scene& scene, const NamedPlacement& p,
                    const BenchObject& object, const BenchInsertOptions& o, const fs::path& dir) {
  CaseResult r{p.name, object.name};
  insert::InsertRequest request;
  request.x = p.x, request.y = p.y;
  request.spp = o.spp;
  request.seed = o.seed;
  const auto start = std::chrono::steady_clock::now();
  const Image truth =
      true_render(scene, insert::place_object(object.scene, insert::surface_at(v, p.x, p.y), request.placement), v, o);
  r.truth_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  fs::create_directories(dir);
  write_image(dir / "truth.exr", truth);
  write_image(dir / "truth.png", linear_to_display(truth, float(v.exposure_stops), v.display_view));
  Image region;
  for (const std::string lighting : {"gt", "global", "constant"}) {
    request.lighting.source = lighting;
    const insert::InsertResult result = insert::insert_object(v, object.scene, request);
    if (region.empty()) region = result.with_object.mask;  // the object and its support surface
    insert::write_insert_outputs(dir / lighting, v, result);
    r.rmse.emplace_back(lighting, masked_rmse(result.composite.color, truth, region));
  }
  return r;
}

std::string markdown_table(const std::vector<CaseResult>& results) {
  std::string t = "| placement | object | GT probes (varying) | global probe | constant | truth render s |\n"
                  "| --- | --- | --- | --- | --- | --- |\n";
  for (const CaseResult& r : results)
    t += fmt::format("| {} | {} | {:.4f} | {:.4f} | {:.4f} | {:.1f} |\n", r.placement, r.object, r.rmse[0].second,
                     r.rmse[1].second, r.rmse[2].second, r.truth_seconds);
  return t;
}

void run(const BenchInsertOptions& o) {
  const insert::InsertView v = insert::read_insert_view(o.view);
  const scenes::Scene scene = scenes::load_gltf(o.scene);
  std::vector<BenchObject> objects;
  for (const eval::SphereMaterial& m : eval::sphere_materials()) objects.push_back({m.key, sphere_object(m, o.sphere_radius)});
  if (!o.object.empty()) objects.push_back({fs::path(o.object).stem().string(), scenes::load_gltf(o.object)});
  std::vector<CaseResult> results;
  nlohmann::json record = {{"view", o.view}, {"scene", o.scene}, {"spp", o.spp}, {"truth_spp", o.truth_spp},
                           {"machine", machine_description()}};
  for (const NamedPlacement& p : find_placements(v))
    for (const BenchObject& object : objects) {
      spdlog::info("bench insert: {} on the {} (pixel {}, {})", object.name, p.name, p.x, p.y);
      results.push_back(run_case(v, scene, p, object, o, fs::path(o.out) / p.name / object.name));
      nlohmann::json c = {{"placement", p.name}, {"pixel", {p.x, p.y}}, {"object", object.name},
                          {"truth_seconds", results.back().truth_seconds}};
      for (const auto& [lighting, rmse] : results.back().rmse) c["rmse"][lighting] = rmse;
      record["cases"].push_back(c);
    }
  const std::string table = markdown_table(results);
  write_file_atomic(fs::path(o.out) / "insert_bench.md", table);
  write_file_atomic(fs::path(o.out) / "insert_bench.json", record.dump(2) + "\n");
  fmt::print("{}", table);
}

}  // namespace

void add_bench_insert_command(CLI::App& bench) {
  auto o = std::make_shared<BenchInsertOptions>();
  auto* cmd = bench.add_subcommand("insert", "object insertion against the scene re-rendered with the object in it");
  cmd->add_option("view", o->view, "view folder rendered with --probes from --scene")
      ->required()
      ->check(CLI::ExistingDirectory);
  cmd->add_option("--scene", o->scene, "the view's glTF scene")->required()->check(CLI::ExistingFile);
  cmd->add_option("--object", o->object, "an extra (textured) glTF object to score besides the three spheres");
  cmd->add_option("--out", o->out, "output folder")->capture_default_str();
  cmd->add_option("--spp", o->spp, "paths per pixel of the composites' local renders")->capture_default_str();
  cmd->add_option("--truth-spp", o->truth_spp, "paths per pixel of the true render")->capture_default_str();
  cmd->add_option("--radius", o->sphere_radius, "sphere radius, metres")->capture_default_str();
  cmd->add_option("--seed", o->seed, "random seed")->capture_default_str();
  cmd->callback([o] { run(*o); });
}

}  // namespace phyir::cli
