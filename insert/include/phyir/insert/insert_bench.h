#pragma once
// The insertion benchmark behind `phyir bench insert` (docs/insert.md#benchmark-phyir-bench-insert),
// split by concept: where objects go in the room (bench_placements.cpp), one placement x
// object scored over seeds (bench_case.cpp), the object moved along a path (bench_path.cpp),
// and the tables (bench_report.cpp). The truth is the scene path traced with the object in it.
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "phyir/insert/insert_object.h"
#include "phyir/insert/insert_scores.h"
#include "phyir/render/environment_light.h"
#include "phyir/scenes/scene.h"

namespace phyir::insert {

struct BenchSettings {
  std::vector<std::string> lightings = {"gt", "global", "constant"};  // bench_lighting labels
  int spp = 64;           // the composites' local renders
  int truth_spp = 512;    // the true render with the object in the scene
  int seeds = 3;          // seeds 1..N per case
  int path_steps = 0;     // > 1: the floor path case with this many frames
  int path_stride = 2;    // pixels between path frames
  std::filesystem::path predicted_dir;  // the `predicted` label's prediction folder (`phyir infer`)
};

struct BenchPlacement {
  std::string name;
  int x = -1, y = -1;
  std::string note;  // why it is where it is (the lamp or window it is near)
};

// The scene the view was rendered from, and its environment light (null: none), as the
// renderer's job loads it.
struct BenchRoom {
  scenes::Scene scene;
  std::unique_ptr<render::EnvironmentLight> environment;
};

struct BenchObject {
  std::string name;
  scenes::Scene scene;
};

// A sphere of `radius` metres in one of Table 10's materials (eval::sphere_materials()), named
// by the material's key, standing on y = 0.
BenchObject sphere_object(const std::string& material_key, float radius);
// The three of Table 10: diffuse, matte silver, mirror silver.
std::vector<BenchObject> table10_spheres(float radius);

// The placements of the view (floor, table, lamp, window) for an object `half_width` metres
// across (half) and `height` tall; `skipped` gets one line per placement the room lacks.
std::vector<BenchPlacement> find_placements(const InsertView& view, const scenes::Scene& scene,
                                            float half_width, float height, std::vector<std::string>& skipped);

// Whether an upright box (`half_width` about the point, `height` above it) standing at `p`
// touches no triangle of `scene` (triangle bounding boxes: conservative).
bool clear_of_scene(const scenes::Scene& scene, const glm::vec3& p, float half_width, float height);

// A bench lighting label as a request: gt, global, constant, an HDR file, or the GT probes'
// variants gt_plane (only the support plane's probes blended), gt_p4 (blend power 4), gt_point
// (distances to the vertex instead of the ray), gt_foot (between foot points on the support
// plane) and gt_projected (no local blend).
LightingRequest bench_lighting(const std::string& label);

// The scene rendered with `placed` really in it, from the view's camera, at `pixels` (each as a
// full render gives it: insert/pixel_render.h); elsewhere the view's colour.
Image true_render(const BenchRoom& room, const scenes::Scene& placed, const InsertView& view, int spp,
                  uint64_t seed, const std::vector<glm::ivec2>& pixels);

// The pixels the truth is rendered at: the scored region and the SSIM window around it.
inline constexpr int kTruthMarginPixels = 3;

// One placement x object: per lighting, its scores over the seeds.
struct CaseScores {
  std::string placement, object;
  std::map<std::string, std::vector<double>> rmse, ssim;  // per lighting, one per seed
  std::vector<double> truth_seconds, composite_seconds;
};

CaseScores run_case(const InsertView& view, const BenchRoom& room, const BenchPlacement& placement,
                    const BenchObject& object, const BenchSettings& options, const std::filesystem::path& dir);

// The object moved along the floor: per lighting, the temporal scores.
struct PathScores {
  std::string object;
  std::vector<glm::ivec2> pixels;
  std::map<std::string, double> change_error;  // per lighting
  double truth_rms_change = 0.0;
  std::map<std::string, double> rms_change;  // per lighting
};

PathScores run_path(const InsertView& view, const BenchRoom& room, const BenchPlacement& start,
                    const BenchObject& object, const BenchSettings& options, const std::filesystem::path& dir);

// insert_bench.md's tables and insert_bench.json's cases.
std::string cases_table(const std::vector<CaseScores>& cases, const std::vector<std::string>& lightings);
std::string path_table(const std::vector<PathScores>& paths, const std::vector<std::string>& lightings);
nlohmann::json case_record(const CaseScores& c, const BenchPlacement& p);
nlohmann::json path_record(const PathScores& p);

}  // namespace phyir::insert
