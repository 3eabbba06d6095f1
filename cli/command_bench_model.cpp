// phyir bench model: forward and forward+backward time and peak memory of each module of the
// network (GMNet, GSNet, LNet, rendering layer, full inference) at the default and the paper's
// resolution: CSV, a markdown table and JSON. docs/commands/bench.md, docs/model-results.md ("Cost").
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <memory>
#include <sstream>
#include <thread>

#include <fmt/format.h>

#include "commands.h"
#include "flag_registry.h"
#include "torch_handoff.h"
#include "phyir/core/atomic_file.h"
#include "phyir/core/log.h"

#ifdef PHYIR_HAVE_MODEL
#include <nlohmann/json.hpp>

#include "phyir/model/benchmark.h"
#include "phyir/model/training.h"
#endif

namespace phyir::cli {

#ifdef PHYIR_HAVE_MODEL

namespace {

struct BenchModelFlags {
  model::ModelBenchOptions options;
  std::string out = "bench-model";
};

std::string cpu_name() {
  std::ifstream cpuinfo("/proc/cpuinfo");
  std::string line;
  while (std::getline(cpuinfo, line))
    if (line.rfind("model name", 0) == 0) return line.substr(line.find(':') + 2);
  return "unknown CPU";
}

double load_average() {
  double l = -1;
  if (FILE* f = std::fopen("/proc/loadavg", "r")) {
    if (std::fscanf(f, "%lf", &l) != 1) l = -1;
    std::fclose(f);
  }
  return l;
}

// libgomp reads OMP_WAIT_POLICY when it loads, before main: if it is unset, run this command
// again with it set to passive (spinning OpenMP threads slow torch several-fold on a shared
// machine, docs/model-results.md).
void ensure_passive_openmp() {
  if (std::getenv("OMP_WAIT_POLICY")) return;
  std::ifstream f("/proc/self/cmdline", std::ios::binary);
  const std::string all((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  std::vector<std::string> args;
  for (size_t b = 0; b < all.size();) {
    const size_t e = all.find('\0', b);
    args.push_back(all.substr(b, e - b));
    b = e == std::string::npos ? all.size() : e + 1;
  }
  if (args.empty()) return;
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  setenv("OMP_WAIT_POLICY", "passive", 1);
  execv("/proc/self/exe", argv.data());
  spdlog::warn("could not re-run with OMP_WAIT_POLICY=passive; timings may suffer from spinning threads");
}

std::string ms_or_dash(double v) { return v < 0 ? "-" : fmt::format("{:.0f}", v); }
std::string mib_or_dash(double v) { return v < 0 ? "-" : fmt::format("{:.0f}", v); }

void run(const BenchModelFlags& f) {
  ensure_passive_openmp();
  spdlog::info("bench model: {} thread(s), settings {}, LNet heads {}, load average {:.1f}", f.options.threads,
               fmt::join(f.options.settings, ","), fmt::join(f.options.lnet_heads, ","), load_average());
  const auto rows = model::benchmark_modules(f.options, [](const model::ModuleCost& c) {
    spdlog::info("{:8s} {:13s} {:6s} forward {:>7s} ms (CPU {:>7s} ms, {:>5s} MiB), forward+backward {:>7s} ms "
                 "(CPU {:>7s} ms, {:>5s} MiB)  [{}]",
                 c.setting, c.module, c.variant, ms_or_dash(c.forward_ms), ms_or_dash(c.forward_cpu_ms),
                 mib_or_dash(c.forward_peak_mib), ms_or_dash(c.forward_backward_ms),
                 ms_or_dash(c.forward_backward_cpu_ms), mib_or_dash(c.forward_backward_peak_mib), c.shape);
  });
  std::ostringstream csv, md;
  csv << "setting,module,variant,shape,forward_ms,forward_cpu_ms,forward_peak_mib,forward_backward_ms,"
         "forward_backward_cpu_ms,forward_backward_peak_mib\n";
  md << "| setting | module | LNet head | sizes | forward ms (CPU ms) | forward peak MiB | forward+backward ms (CPU ms) | "
        "forward+backward peak MiB |\n| --- | --- | --- | --- | --- | --- | --- | --- |\n";
  nlohmann::json j = {{"machine", cpu_name()},
                      {"hardware_threads", std::thread::hardware_concurrency()},
                      {"threads", f.options.threads},
                      {"load_average_at_end", load_average()},
                      {"omp_wait_policy", std::getenv("OMP_WAIT_POLICY") ? std::getenv("OMP_WAIT_POLICY") : ""},
                      {"timing", "best wall time of the timed runs after one warm-up run, batch 1"},
                      {"peak_memory", model::peak_memory_method()},
                      {"rows", nlohmann::json::array()}};
  for (const auto& c : rows) {
    csv << c.setting << ',' << c.module << ',' << c.variant << ",\"" << c.shape << "\"," << c.forward_ms << ','
        << c.forward_cpu_ms << ',' << c.forward_peak_mib << ',' << c.forward_backward_ms << ','
        << c.forward_backward_cpu_ms << ',' << c.forward_backward_peak_mib << '\n';
    auto both = [](double wall, double cpu) { return wall < 0 ? std::string("-") : ms_or_dash(wall) + " (" + ms_or_dash(cpu) + ")"; };
    md << "| " << c.setting << " | " << c.module << " | " << (c.variant.empty() ? "-" : c.variant) << " | "
       << c.shape << " | " << both(c.forward_ms, c.forward_cpu_ms) << " | " << mib_or_dash(c.forward_peak_mib) << " | "
       << both(c.forward_backward_ms, c.forward_backward_cpu_ms) << " | " << mib_or_dash(c.forward_backward_peak_mib)
       << " |\n";
    j["rows"].push_back({{"setting", c.setting}, {"module", c.module}, {"variant", c.variant}, {"shape", c.shape},
                         {"forward_ms", c.forward_ms}, {"forward_peak_mib", c.forward_peak_mib},
                         {"forward_cpu_ms", c.forward_cpu_ms}, {"forward_backward_cpu_ms", c.forward_backward_cpu_ms},
                         {"forward_backward_ms", c.forward_backward_ms},
                         {"forward_backward_peak_mib", c.forward_backward_peak_mib}});
  }
  const std::filesystem::path out(f.out);
  std::filesystem::create_directories(out);
  write_file_atomic(out / "model_bench.csv", csv.str());
  write_file_atomic(out / "model_bench.md", md.str());
  write_file_atomic(out / "model_bench.json", j.dump(2) + "\n");
  std::printf("%s", md.str().c_str());
  spdlog::info("wrote {}/model_bench.{{csv,md,json}}", out.string());
}

}  // namespace

void add_bench_model_command(CLI::App& bench) {
  auto f = std::make_shared<BenchModelFlags>();
  auto* cmd = bench.add_subcommand(
      "model", "time and peak memory of GMNet, GSNet, LNet, the rendering layer and full inference "
               "(forward, forward+backward) at the default and the paper's resolution");
  cmd->add_option("--out", f->out, "folder for model_bench.csv, .md and .json")->capture_default_str();
  const model::ModelConfig c;  // the default setting's sizes
  sets(cmd, "threads", cmd->add_option("--threads", f->options.threads, "torch threads"))->capture_default_str();
  sets(cmd, "repeats", cmd->add_option("--repeats", f->options.repeats, "timed runs after the warm-up (best is kept)"))
      ->capture_default_str();
  sets(cmd, "settings",
       cmd->add_option("--settings", f->options.settings,
                       fmt::format("default (input {}x{}, rendering {}x{}, {}x{} probes, {}/{} samples) and/or paper "
                                   "(256x512, 128x256, 16x32, 512/256)",
                                   c.input_height, c.input_width, c.render_height, c.render_width, c.probe_height,
                                   c.probe_width, c.diffuse_samples, c.specular_samples)))
      ->delimiter(',')
      ->capture_default_str();
  sets(cmd, "lnet_heads",
       cmd->add_option("--lnet-heads", f->options.lnet_heads, "LNet output heads to measure: paper and/or light"))
      ->delimiter(',')
      ->capture_default_str();
  cmd->add_flag("!--no-backward", f->options.backward, "forward only");
  cmd->add_option("--seed", f->options.seed, "random seed of the weights and inputs")->capture_default_str();
  cmd->callback([f] { run(*f); });
}

#else

// `phyir` lists the command in --help. With the network built, main() hands the command to
// phyir-torch before parsing (torch_handoff.h); without it, the callback says it was not built.
void add_bench_model_command(CLI::App& bench) {
  auto* cmd = bench.add_subcommand("model", "time and memory of the network's modules" + torch_build_note());
  // Every argument after the command is the network command's: kept here, not passed up to
  // phyir (main() sets fallthrough, which would refuse them there).
  cmd->fallthrough(false)->prefix_command();
  cmd->callback([] { run_in_torch_cli("bench model"); });
}

#endif

}  // namespace phyir::cli
