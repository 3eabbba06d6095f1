// phyir bench: what accuracy costs in time. Long-running studies, never part of the tests.
//   convergence  RMSE against a converged reference versus seconds, per spp (CSV + PNG)
//   effects      the scene's specialised kernel versus every effect forced on
//   throughput   integrator rays/s as a fraction of raw Embree throughput
#include <tbb/global_control.h>
#include <tbb/info.h>

#include <cstdlib>
#include <memory>
#include <sstream>

#include "bench_suite_runner.h"
#include "camera_flags.h"
#include "commands.h"
#include "sampling_flags.h"
#include "phyir/core/atomic_file.h"
#include "phyir/core/error.h"
#include "phyir/core/machine.h"
#include "phyir/core/image_io.h"
#include "phyir/core/log.h"
#include "phyir/render/render_job.h"
#include "phyir/render/studies.h"
#include "phyir/scenes/gltf_loader.h"

namespace phyir::cli {

namespace fs = std::filesystem;

namespace {

render::RenderSettings colour_only() {
  render::RenderSettings s;
  s.aovs = false;
  return s;
}

struct BenchFlags {
  std::string scene;
  std::string suite;                 // suite.json: measure on every scene of it instead
  std::optional<glm::vec3> camera;   // from the suite; else the scene's camera
  std::string out = "bench-out";
  int width = 256;
  int height = 128;
  int threads = 0;
  int reference_spp = 4096;
  render::RenderSettings settings = colour_only();  // seed and bounces from the flags
  std::vector<int> spp_list = {1, 2, 4, 8, 16, 32, 64, 128, 256};
  int repeats = 3;
};

struct Loaded {
  scenes::Scene scene;
  std::unique_ptr<render::RenderScene> render_scene;
  render::CameraModel camera;
};

std::unique_ptr<Loaded> load(const BenchFlags& f) {
  auto l = std::make_unique<Loaded>();
  l->scene = scenes::load_gltf(f.scene);
  l->render_scene = std::make_unique<render::RenderScene>(l->scene, render::scene_environment(l->scene));
  render::RenderJob job;
  job.width = f.width;
  job.height = f.height;
  job.camera_position = f.camera;
  l->camera = render::job_camera(job, l->scene, nullptr);
  return l;
}

void add_common(CLI::App* cmd, BenchFlags& f) {
  cmd->add_option("scene", f.scene, "glTF scene to measure on (or --suite)")->check(CLI::ExistingFile);
  cmd->add_option("--suite", f.suite, "suite.json of 'phyir bench suite': measure on every scene, into OUT/<name>/")
      ->check(CLI::ExistingFile);
  cmd->add_option("--out", f.out, "folder for CSV, PNG and JSON results")->capture_default_str();
  add_image_size_flags(cmd, f.width, f.height);
  add_threads_flag(cmd, f.threads);
  add_max_bounces_flag(cmd, f.settings.path.max_bounces);
  add_light_subpaths_flag(cmd, f.settings.path.light_subpaths);
  add_seed_flag(cmd, f.settings.seed);
}

void run_convergence(const BenchFlags& f) {
  auto l = load(f);
  fs::create_directories(f.out);
  const fs::path reference_path = fs::path(f.out) / "reference.exr";
  render::RenderSettings s = f.settings;
  Image reference;
  if (fs::exists(reference_path)) {
    reference = read_image(reference_path);
    spdlog::info("reusing converged reference {}", reference_path.string());
  }
  if (reference.width != f.width || reference.height != f.height) {
    spdlog::info("rendering the converged reference at {} spp", f.reference_spp);
    s.spp = f.reference_spp;
    s.seed = f.settings.seed + 1000;
    reference = render::render_view(*l->render_scene, l->camera, s).film.color();
    write_image(reference_path, reference);
    s.seed = f.settings.seed;
  }
  const auto points = render::convergence_study(*l->render_scene, l->camera, s, f.spp_list, reference);
  std::ostringstream csv;
  csv << "spp,seconds,rmse,relative_rmse,rays_per_second\n";
  for (const auto& p : points) {
    csv << p.spp << ',' << p.seconds << ',' << p.rmse << ',' << p.relative_rmse << ',' << p.rays_per_second << '\n';
    spdlog::info("spp {:5d}: {:8.3f} s, RMSE {:.5f}, relative RMSE {:.4f}", p.spp, p.seconds, p.rmse, p.relative_rmse);
  }
  const fs::path csv_path = fs::path(f.out) / "convergence.csv";
  write_file_atomic(csv_path, csv.str());
  nlohmann::json rows = nlohmann::json::array();
  for (const auto& p : points)
    rows.push_back({{"spp", p.spp}, {"seconds", p.seconds}, {"relative_rmse", p.relative_rmse}});
  write_file_atomic(fs::path(f.out) / "convergence.json",
                    nlohmann::json{{"scene", f.scene}, {"points", rows}, {"machine", machine_description()}}.dump(2) + "\n");
  write_file_atomic(fs::path(f.out) / "machine.txt", machine_description() + "\n");
  const fs::path script = fs::path(PHYIR_SOURCE_ROOT) / "scripts" / "plot_convergence.py";
  const std::string cmd = "/usr/bin/python3 '" + script.string() + "' '" + csv_path.string() + "' '" +
                          (fs::path(f.out) / "convergence.png").string() + "' '" + machine_description() + "'";
  if (std::system(cmd.c_str()) != 0) spdlog::warn("plot not written: {} failed (python3-matplotlib missing?)", script.string());
  spdlog::info("wrote {}", csv_path.string());
}

void run_effects(const BenchFlags& f) {
  auto l = load(f);
  render::RenderSettings s = f.settings;
  s.spp = 16;
  const auto r = render::compare_effect_kernels(*l->render_scene, l->camera, s, f.repeats);
  nlohmann::json j = {{"scene", f.scene},
                      {"effects", r.specialised.to_json()},
                      {"specialised_seconds", r.specialised_seconds},
                      {"forced_all_seconds", r.forced_seconds},
                      {"saving_fraction", 1.0 - r.specialised_seconds / r.forced_seconds},
                      {"identical_output", r.identical},
                      {"machine", machine_description()}};
  fs::create_directories(f.out);
  write_file_atomic(fs::path(f.out) / "effects.json", j.dump(2) + "\n");
  std::printf("%s\n", j.dump(2).c_str());
  if (!r.identical) fail("specialised and forced kernels gave different images: a kernel is wrong");
}

void run_throughput(const BenchFlags& f) {
  auto l = load(f);
  render::RenderSettings s = f.settings;
  s.spp = 16;
  const auto r = render::measure_throughput(*l->render_scene, l->camera, s);
  nlohmann::json j = {{"scene", f.scene},
                      {"integrator_rays_per_second", r.integrator_rays_per_second},
                      {"embree_single_rays_per_second", r.embree_single_rays_per_second},
                      {"embree_packet_rays_per_second", r.embree_packet_rays_per_second},
                      {"fraction_of_single", r.integrator_rays_per_second / r.embree_single_rays_per_second},
                      {"fraction_of_packet", r.integrator_rays_per_second / r.embree_packet_rays_per_second},
                      {"replayed_rays", r.replayed_rays},
                      {"machine", machine_description()}};
  fs::create_directories(f.out);
  write_file_atomic(fs::path(f.out) / "throughput.json", j.dump(2) + "\n");
  std::printf("%s\n", j.dump(2).c_str());
}

}  // namespace

void add_bench_command(CLI::App& app) {
  auto* bench = app.add_subcommand("bench", "Measure what accuracy costs in time (long; not part of the tests)");
  bench->require_subcommand(1);
  auto f = std::make_shared<BenchFlags>();
  auto with_threads = [f](void (*run)(const BenchFlags&), const char* result_file) {
    return [f, run, result_file] {
      const int threads = f->threads > 0 ? f->threads : tbb::info::default_concurrency();
      tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
      run_scene_or_suite(*f, run, result_file, "phyir bench");
    };
  };
  auto* conv = bench->add_subcommand("convergence", "RMSE against a converged reference versus seconds, for increasing spp");
  add_common(conv, *f);
  conv->add_option("--spp-list", f->spp_list, "spp values to measure")->delimiter(',')->capture_default_str();
  conv->add_option("--reference-spp", f->reference_spp, "spp of the converged reference")->capture_default_str();
  conv->callback(with_threads(&run_convergence, "convergence.json"));
  auto* eff = bench->add_subcommand("effects", "time saved by the scene's specialised kernel versus every effect forced on");
  add_common(eff, *f);
  eff->add_option("--repeats", f->repeats, "best of this many runs")->capture_default_str();
  eff->callback(with_threads(&run_effects, "effects.json"));
  auto* thr = bench->add_subcommand("throughput", "integrator rays/s as a fraction of raw Embree throughput");
  add_common(thr, *f);
  thr->callback(with_threads(&run_throughput, "throughput.json"));
  add_bench_probes_command(*bench);
  add_bench_suite_command(*bench);
  add_bench_insert_command(*bench);
  add_bench_model_command(*bench);
}

}  // namespace phyir::cli
