#pragma once
// `phyir bench insert` (command_bench_insert.cpp), split by concept: where objects go in the
// room (bench_insert_placements.cpp), one placement x object scored over seeds
// (bench_insert_cases.cpp), the object moved along a path (bench_insert_path.cpp), and the
// tables (bench_insert_report.cpp). docs/insert.md#benchmark-phyir-bench-insert.
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "phyir/insert/insert_object.h"
#include "phyir/insert/insert_scores.h"
#include "phyir/scenes/scene.h"

namespace phyir::cli {

struct BenchInsertOptions {
  std::string view, scene, out = "bench-insert";
  std::vector<std::string> objects;   // extra glTF objects besides the spheres
  std::vector<std::string> assets;    // furniture library ids, converted to glTF
  std::string assets_dir;             // the library (empty: the toolkit's default)
  float asset_height = 0.3f;          // metres: library pieces scaled to this height
  std::vector<std::string> only_placements, only_objects;  // empty: all
  std::vector<std::string> lightings = {"gt", "global", "constant"};
  int spp = 64;           // the composites' local renders
  int truth_spp = 512;    // the true render with the object in the scene
  int seeds = 3;          // seeds 1..N per case
  int path_steps = 0;     // > 1: the floor path case with this many frames
  int path_stride = 2;    // pixels between path frames
  float sphere_radius = 0.15f;
};

struct NamedPlacement {
  std::string name;
  int x = -1, y = -1;
  std::string note;  // why it is where it is (the lamp or window it is near)
};

struct BenchObject {
  std::string name;
  scenes::Scene scene;
};

// The placements of the view (floor, table, lamp, window) for an object `half_width` metres
// across (half) and `height` tall; `skipped` gets one line per placement the room lacks.
std::vector<NamedPlacement> find_placements(const insert::InsertView& view, const scenes::Scene& scene,
                                            float half_width, float height, std::vector<std::string>& skipped);

// Whether an upright box (`half_width` about the point, `height` above it) standing at `p`
// touches no triangle of `scene` (triangle bounding boxes: conservative).
bool clear_of_scene(const scenes::Scene& scene, const glm::vec3& p, float half_width, float height);

// A bench lighting label as a request: gt, global, constant, an HDR file, or the GT probes'
// variants gt_plane (only the support plane's probes blended) and gt_projected (no local blend).
insert::LightingRequest bench_lighting(const std::string& label);

// The scene rendered with `placed` really in it, from the view's camera.
Image true_render(const scenes::Scene& scene, const scenes::Scene& placed, const insert::InsertView& view, int spp,
                  uint64_t seed);

// One placement x object: per lighting, its scores over the seeds.
struct CaseScores {
  std::string placement, object;
  std::map<std::string, std::vector<double>> rmse, ssim;  // per lighting, one per seed
  std::vector<double> truth_seconds, composite_seconds;
};

CaseScores run_case(const insert::InsertView& view, const scenes::Scene& scene, const NamedPlacement& placement,
                    const BenchObject& object, const BenchInsertOptions& options, const std::filesystem::path& dir);

// The object moved along the floor: per lighting, the temporal scores.
struct PathScores {
  std::string object;
  std::vector<glm::ivec2> pixels;
  std::map<std::string, double> change_error;  // per lighting
  double truth_rms_change = 0.0;
  std::map<std::string, double> rms_change;  // per lighting
};

PathScores run_path(const insert::InsertView& view, const scenes::Scene& scene, const NamedPlacement& start,
                    const BenchObject& object, const BenchInsertOptions& options, const std::filesystem::path& dir);

// insert_bench.md's tables and insert_bench.json's cases.
std::string cases_table(const std::vector<CaseScores>& cases, const std::vector<std::string>& lightings);
std::string path_table(const std::vector<PathScores>& paths, const std::vector<std::string>& lightings);
nlohmann::json case_record(const CaseScores& c, const NamedPlacement& p);
nlohmann::json path_record(const PathScores& p);

}  // namespace phyir::cli
