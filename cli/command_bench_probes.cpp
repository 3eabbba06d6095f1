// phyir bench probes: what per-pixel light probes cost and how wrong they are, per mode and
// setting, against a converged reference (render/probe_study.h has the method, docs/probes-accuracy.md
// the results). This file parses the settings, runs the study and writes its tables.
#include <tbb/global_control.h>
#include <tbb/info.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <memory>
#include <optional>
#include <sstream>

#include "bench_probes_exposure.h"
#include "bench_probes_summary.h"
#include "bench_suite_runner.h"
#include "commands.h"
#include "flag_registry.h"
#include "probe_flags.h"
#include "sampling_flags.h"
#include "phyir/core/atomic_file.h"
#include "phyir/core/error.h"
#include "phyir/core/image_io.h"
#include "phyir/core/log.h"
#include "phyir/core/machine.h"
#include "phyir/render/environment_light.h"
#include "phyir/render/probe_study.h"
#include "phyir/render/render_job.h"
#include "phyir/scenes/gltf_loader.h"

namespace phyir::cli {

namespace fs = std::filesystem;

namespace {

render::ProbeSettings bench_base() {
  render::ProbeSettings base;
  base.progress = false;
  // The punctual lights' texels are exact and the same in every mode: left out, so that the
  // error is that of the estimated light alone and not diluted by them.
  base.punctual_lights = false;
  return base;
}

struct BenchProbeFlags {
  std::string scene;
  std::string suite;                 // suite.json: measure on every scene of it instead
  std::optional<glm::vec3> camera;   // from the suite; else the scene's camera
  std::string out = "bench-probes";
  render::ProbeSettings base = bench_base();  // grid, offset, photons, bounces and seed from the flags
  std::vector<std::string> res_list = {
      fmt::format("{}x{}", render::ProbeLayout().res_height, render::ProbeLayout().res_width)};
  // The settings of docs/probes-accuracy.md's table.
  std::vector<std::string> configs = {"cache:2:32", "cache:4:64", "cache:4:256", "cache:8:64",
                                      "path:4",     "path:16",    "path:64"};
  render::ProbeStudyOptions study;  // reference spp and probes, probe indices, subset only
  int threads = 0;
  int width = 512;  // the camera the probes are placed from
  int height = 256;
};

constexpr const char* kConfigSyntax =
    "MODE:SPP[:CACHE_SPP[:CELL_M[:SEED[:DIRECT_CELLS[:SPREAD[:SHARE_RADIUS[:SHARE_PARALLAX]]]]]]][@ERROR[:fixed]]";

// An entry's "@ERROR[:fixed]": --probe-error ERROR, and with "fixed" --no-probe-progressive.
void parse_error_target(const std::string& config, const std::string& text, render::ProbeSettings* s) {
  const size_t colon = text.find(':');
  const std::string tail = colon == std::string::npos ? "" : text.substr(colon + 1);
  if (!tail.empty() && tail != "fixed") fail("--configs '{}': '{}' after the error target is not 'fixed'", config, tail);
  try {
    s->target_error = std::stof(text.substr(0, colon));
  } catch (const std::exception&) {
    fail("--configs '{}': the error target after '@' must be a number", config);
  }
  s->progressive = tail.empty();
}

// One --configs entry over `base`: SEED is added to the base's seed.
render::ProbeStudySetting parse_config(const std::string& entry, const render::ProbeSettings& base) {
  render::ProbeStudySetting c{entry, base};
  render::ProbeSettings& s = c.settings;
  const size_t at = entry.find('@');
  if (at != std::string::npos) parse_error_target(entry, entry.substr(at + 1), &s);
  const std::string text = entry.substr(0, at);
  std::vector<std::string> parts;
  std::stringstream in(text);
  for (std::string part; std::getline(in, part, ':');) parts.push_back(part);
  if (parts.size() < 2 || parts.size() > 9) fail("--configs '{}' is not {}", text, kConfigSyntax);
  try {
    s.spp = std::stoi(parts[1]);
    if (parts.size() > 2) s.cache.samples_per_cell = std::stoi(parts[2]);
    if (parts.size() > 3) s.cache.cell_size = std::stof(parts[3]);
    if (parts.size() > 4) s.seed = base.seed + std::stoull(parts[4]);
    if (parts.size() > 5) s.cache.direct_distance_cells = std::stof(parts[5]);
    if (parts.size() > 6) s.spread_threshold = std::stof(parts[6]);
    if (parts.size() > 7) s.sharing.radius = std::stoi(parts[7]);
    if (parts.size() > 8) s.sharing.parallax_texels = std::stof(parts[8]);
  } catch (const std::exception&) {
    fail("--configs '{}': SPP, CACHE_SPP, CELL_M, SEED, DIRECT_CELLS, SPREAD, SHARE_RADIUS and SHARE_PARALLAX must be "
         "numbers",
         text);
  }
  try {
    s.mode = render::parse_probe_mode(parts[0]);
    s.validate();
  } catch (const SettingError& e) {
    fail("--configs '{}': {}", text, e.what());  // the field of the entry, by its setting's name
  }
  return c;
}

void log_breakdown(const std::string& config, const nlohmann::json& b) {
  spdlog::info("{}: where the squared error is (share, relative RMSE, bias, noise, mean error):", config);
  auto line = [](const std::string& name, const nlohmann::json& j) {
    spdlog::info("  {:<24} {:>6} texels  {:5.1f}%  rmse {:.4f}  bias {:.4f}  noise {:.4f}  mean {:+.4f}", name,
                 j["texels"].get<size_t>(), 100.0 * j["share_of_squared_error"].get<double>(),
                 j["relative_rmse"].get<double>(), j.value("bias", -1.0), j.value("noise", -1.0),
                 j["mean_error_of_own_mean"].get<double>());
  };
  for (const auto& [name, j] : b["classes"].items()) line(name, j);
  for (const auto& j : b["probes"]) {
    // A scene without emissive triangles or punctual lights at a distance (the sun) has none.
    const float light_m = j["nearest_light_m"].is_number() ? j["nearest_light_m"].get<float>() : -1.0f;
    const std::string light = std::isfinite(light_m) && light_m >= 0.0f
                                  ? "light " + std::to_string(int(100.0f * light_m)) + " cm"
                                  : "no light near";
    line("probe " + std::to_string(j["index"].get<int>()) + " (" + light + ")", j);
  }
}

// probes.csv and probes.json as they grow.
struct BenchTables {
  std::ostringstream csv;
  nlohmann::json summary;
  std::string markdown;  // probes_summary.md
};

// Enough for the auto exposure's 95th percentile of the view's colour.
constexpr int kExposureSpp = 16;

std::string size_text(int height, int width) { return fmt::format("{}x{}", height, width); }

void add_row(const BenchProbeFlags& f, const render::ProbeStudy& study, const render::ProbeStudyRow& row,
             const LightingMetrics& lighting, const LightingMetrics& lighting_input, BenchTables& tables) {
  const render::ProbeSettings& t = row.setting.settings;
  const std::string grid = size_text(t.layout.grid_height, t.layout.grid_width);
  const std::string res = size_text(t.layout.res_height, t.layout.res_width);
  const std::string& text = row.setting.name;
  std::string name = text;
  std::replace(name.begin(), name.end(), ':', '-');
  write_image(fs::path(f.out) / ("strip_" + grid + "_" + res + "_" + name + ".exr"), row.strip);
  write_image(fs::path(f.out) / ("strip_" + grid + "_" + res + "_" + name + "_stderr.exr"), row.strip_stderr);
  const double noise = study.reference_noise();
  spdlog::info("{} {} {:>14}: {:8.2f} s ({:8.2f} s CPU){}, relative RMSE {:.4f} (reference noise {:.4f}); "
               "standard error: median |e|/sigma {:.2f} x Gaussian, {:.0f}% within 2 sigma",
               grid, res, text, row.seconds, row.cpu_seconds, row.extrapolated ? " extrapolated" : "",
               row.error.relative_rmse, noise, row.calibration.median_ratio, 100.0 * row.calibration.within_two_sigma);
  spdlog::info("{}: per-probe relative RMSE median {:.4f}, 90th percentile {:.4f} (reference noise {:.4f}, {:.4f})",
               text, row.per_probe.median, row.per_probe.p90, study.reference_noise_per_probe().median,
               study.reference_noise_per_probe().p90);
  log_lighting(text, lighting);
  tables.csv << fs::path(f.scene).stem().string() << ',' << grid << ',' << res << ',' << text << ','
             << render::probe_mode_name(t.mode) << ',' << t.spp << ',' << t.cache.samples_per_cell << ','
             << t.cache.cell_size << ',' << study.computed_probes() << ',' << row.seconds << ',' << row.cpu_seconds
             << ',' << (row.extrapolated ? 1 : 0) << ',' << row.rays << ',' << row.error.relative_rmse << ','
             << row.error.rmse << ',' << noise << ',' << f.study.reference_spp << ',' << study.subset().size() << ','
             << row.stats.cache_cells << ',' << row.stats.cache_fallbacks << ',' << row.per_probe.median << ','
             << row.per_probe.p90 << ',' << lighting.mae[0] << ',' << lighting.mae[1] << ',' << lighting.mae[2] << ','
             << lighting.ssim << '\n';
  tables.summary["rows"].push_back({{"resolution", res}, {"config", text}, {"seconds", row.seconds},
                                    {"cpu_seconds", row.cpu_seconds}, {"extrapolated", row.extrapolated},
                                    {"relative_rmse", row.error.relative_rmse}, {"reference_noise", noise},
                                    {"calibration", row.calibration.to_json()},
                                    {"stats", row.stats.to_json()},
                                    {"per_probe_relative_rmse",
                                     {{"median", row.per_probe.median}, {"p90", row.per_probe.p90},
                                      {"values", row.per_probe.relative_rmse}}},
                                    {"lighting", lighting.to_json()},
                                    {"lighting_input_units", lighting_input.to_json()}});
  // Keep what was measured so far, in case the run is interrupted.
  write_file_atomic(fs::path(f.out) / "probes.csv", tables.csv.str());
}

// Every configuration at one probe resolution.
void measure_resolution(const BenchProbeFlags& f, const render::RenderScene& scene, const render::CameraModel& camera,
                        const render::Effects& effects, const std::string& res, double input_stops,
                        BenchTables& tables) {
  render::ProbeStudyOptions options = f.study;
  options.scene = f.scene;
  options.base = f.base;
  view::parse_size(res, "--res-list", &options.base.layout.res_height, &options.base.layout.res_width);
  render::ProbeStudy study(scene, camera, effects, options);
  const std::string tag = study.tag();
  const std::string canonical = size_text(options.base.layout.res_height, options.base.layout.res_width);
  tables.summary["subsets"][canonical] = {{"reference", "reference_" + tag + "_half{0,1}.exr"},
                                          {"probes", study.subset_json()}};
  write_file_atomic(fs::path(f.out) / ("subset_" + tag + ".json"), study.subset_json().dump(1) + "\n");
  study.make_reference(f.out);
  // The paper's lighting metrics with eval's default spheres (docs/probes_lighting_metrics.md).
  const eval::RelightSettings spheres;
  const ReferenceLighting reference = reference_lighting(study, spheres, input_stops);
  log_lighting("reference half 0 vs half 1", reference.halves);
  log_lighting("relighting's own noise (the reference's spheres, another seed)", reference.relight_noise);
  tables.summary["reference_lighting"][canonical] = reference_json(reference);
  std::vector<render::ProbeStudyRow> rows;
  std::vector<SummaryRow> summary;
  for (const std::string& text : f.configs) {
    rows.push_back(study.measure(parse_config(text, options.base)));
    const render::ProbeLayout& l = options.base.layout;
    const LitProbes lit = light_probes(rows.back().strip, l.res_height, l.res_width, spheres);
    const LightingMetrics lighting = lighting_metrics(lit, reference.mean);
    const LightingMetrics input = scaled_metrics(lighting, lit, reference.mean, std::exp2(input_stops));
    log_lighting(text + " (input units)", input);
    add_row(f, study, rows.back(), lighting, input, tables);
    summary.push_back(summary_row(rows.back(), lighting, input));
  }
  // Where the error is, per configuration; paired with a run of the same setting under
  // another seed where the configurations hold one.
  for (const render::ProbeStudyRow& row : rows) {
    const render::ProbeStudyRow* other = nullptr;
    for (const render::ProbeStudyRow& candidate : rows)
      if (!other && &candidate != &row && render::same_but_seed(row.setting.settings, candidate.setting.settings))
        other = &candidate;
    const nlohmann::json breakdown = study.breakdown(row, other);
    log_breakdown(row.setting.name, breakdown);
    tables.summary["breakdown"][canonical][row.setting.name] = breakdown;
    SummaryRow& line = summary[size_t(&row - rows.data())];
    line.bias = breakdown["total"].value("bias", -1.0);
    line.noise = breakdown["total"].value("noise", -1.0);
  }
  // Named by the output folder too: a suite's generated rooms are all room_0.gltf.
  const fs::path out = fs::path(f.out).has_filename() ? fs::path(f.out) : fs::path(f.out).parent_path();
  const std::string name = out.filename().string() + ": " + fs::path(f.scene).filename().string();
  const std::string grid = size_text(options.base.layout.grid_height, options.base.layout.grid_width);
  tables.markdown += summary_markdown(name, grid, canonical, reference, summary);
  write_file_atomic(fs::path(f.out) / "probes_summary.md", tables.markdown);
}

void run_bench_probes(const BenchProbeFlags& f) {
  const scenes::Scene scene = scenes::load_gltf(f.scene);
  std::unique_ptr<render::EnvironmentLight> environment = render::scene_environment(scene);
  const bool has_environment = environment != nullptr;
  const render::RenderScene render_scene(scene, std::move(environment));
  render::RenderJob job;
  job.width = f.width;
  job.height = f.height;
  job.camera_position = f.camera;
  const render::CameraModel camera = render::job_camera(job, scene, nullptr);
  const render::Effects effects = render::analyse_effects(scene, has_environment);
  fs::create_directories(f.out);

  const render::ProbeLayout& layout = f.base.layout;
  BenchTables tables;
  tables.csv << "scene,grid,resolution,config,mode,spp,cache_spp,cache_cell_m,probes,seconds,cpu_seconds,extrapolated,"
                "rays,relative_rmse,rmse,reference_noise,reference_spp,subset_probes,cache_cells,cache_fallbacks,"
                "per_probe_median,per_probe_p90,diffuse_mae,matte_silver_mae,mirror_silver_mae,probe_ssim\n";
  tables.summary = {{"scene", f.scene},
                    {"machine", machine_description()},
                    {"grid", size_text(layout.grid_height, layout.grid_width)},
                    {"rows", nlohmann::json::array()}};
  // The unit `phyir eval --radiance input` would score this view in.
  const double input_stops = view_input_stops(render_scene, camera, kExposureSpp);
  tables.summary["input_exposure_stops"] = input_stops;
  for (const std::string& res : f.res_list)
    measure_resolution(f, render_scene, camera, effects, res, input_stops, tables);
  const fs::path csv_path = fs::path(f.out) / "probes.csv";
  write_file_atomic(csv_path, tables.csv.str());
  write_file_atomic(fs::path(f.out) / "probes.json", tables.summary.dump(2) + "\n");
  write_file_atomic(fs::path(f.out) / "machine.txt", machine_description() + "\n");
  const fs::path script = fs::path(PHYIR_SOURCE_ROOT) / "scripts" / "plot_probes.py";
  const std::string cmd = "/usr/bin/python3 '" + script.string() + "' '" + csv_path.string() + "' '" +
                          (fs::path(f.out) / "probes.png").string() + "'";
  if (std::system(cmd.c_str()) != 0) spdlog::warn("plot not written: {} failed (python3-matplotlib missing?)", script.string());
  spdlog::info("wrote {}", csv_path.string());
}

void add_study_flags(CLI::App* cmd, BenchProbeFlags& f) {
  sets(cmd, "probe.res", cmd->add_option("--res-list", f.res_list, "probe resolutions hxw"))
      ->delimiter(',')
      ->capture_default_str();
  cmd->add_option("--configs", f.configs,
                  std::string(kConfigSyntax) +
                      " settings to measure (SEED: added to --seed, for repeated runs; DIRECT_CELLS, SPREAD, "
                      "SHARE_RADIUS, SHARE_PARALLAX: as --probe-cache-direct-cells, --probe-spread-threshold, "
                      "--probe-share-radius, --probe-share-parallax; @ERROR: as --probe-error, ':fixed' as "
                      "--no-probe-progressive)")
      ->delimiter(',')
      ->capture_default_str();
  cmd->add_option("--reference-spp", f.study.reference_spp, "spp of the converged path-mode reference")
      ->capture_default_str();
  cmd->add_option("--reference-probes", f.study.reference_probes, "how many random valid probes the error is measured on")
      ->capture_default_str();
  sets(cmd, "probe_indices",
       cmd->add_option("--probe-indices", f.study.probe_indices,
                       "measure on these probe indices (i * grid width + j) instead of a random subset"))
      ->delimiter(',');
  cmd->add_flag("--subset-only", f.study.subset_only,
                "cache mode renders only the measured probes too (a study aid: its cache then sees only them; times "
                "extrapolated)");
}

}  // namespace

void add_bench_probes_command(CLI::App& bench) {
  auto f = std::make_shared<BenchProbeFlags>();
  auto* cmd = bench.add_subcommand("probes", "light probes: relative RMSE against a converged reference versus seconds, per mode and setting");
  cmd->add_option("scene", f->scene, "glTF scene to measure on (or --suite)")->check(CLI::ExistingFile);
  cmd->add_option("--suite", f->suite, "suite.json of 'phyir bench suite': measure on every scene, into OUT/<name>/")
      ->check(CLI::ExistingFile);
  cmd->add_option("--out", f->out, "folder for probes.csv, probes.png, probes.json, probes_summary.md and the cached references")->capture_default_str();
  add_study_flags(cmd, *f);
  add_threads_flag(cmd, f->threads);
  add_max_bounces_flag(cmd, f->base.path.max_bounces);
  add_light_subpaths_flag(cmd, f->base.path.light_subpaths);
  add_seed_flag(cmd, f->base.seed);
  // The grid the times are measured on, and what every configuration shares.
  add_probe_flags(cmd, f->base, kProbeGrid | kProbeOffset | kProbePhotons | kProbeBalance,
                  {{"--probe-grid", "--grid"}, {"--probe-offset", "--offset"}});
  cmd->callback([f] {
    const int threads = f->threads > 0 ? f->threads : tbb::info::default_concurrency();
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    run_scene_or_suite(*f, &run_bench_probes, "probes.json", "phyir bench probes");
  });
}

}  // namespace phyir::cli
