#pragma once
// Cost of each module of the network: forward and forward+backward wall time
// and peak resident memory, at the default and the paper's resolution. Torch-free, for the CLI
// (`phyir bench model`, cli/command_bench_model.cpp). Docs: docs/model-results.md, "Cost".
#include <functional>
#include <string>
#include <vector>

namespace phyir::model {

struct ModelBenchOptions {
  int threads = 2;
  int repeats = 3;                       // best of this many timed runs after a warm-up run
                                         // (one timed run when the warm-up took over 5 s)
  std::vector<std::string> settings = {"default", "paper"};
  std::vector<std::string> lnet_heads = {"paper", "light"};  // LNet and inference once per head
  bool backward = true;                  // also time forward+backward (training)
  uint64_t seed = 1;
};

struct ModuleCost {
  std::string setting;    // default | paper
  std::string module;     // gmnet | gsnet | lnet | render_layer | inference
  std::string variant;    // the LNet head for lnet and inference, else ""
  std::string shape;      // the sizes measured, e.g. "input 256x512" or "128x256, 16x32 probes, 512/256"
  double forward_ms = -1;            // best wall time, no gradient (eval mode)
  double forward_peak_mib = -1;      // peak resident memory above the resident memory before
  double forward_backward_ms = -1;   // forward + backward of the sum of the outputs (-1: not run)
  double forward_backward_peak_mib = -1;
  // CPU time (user + system, all threads) of one run: on a shared machine the wall time
  // depends on the other jobs; CPU time / threads is what idle cores would take.
  double forward_cpu_ms = -1;
  double forward_backward_cpu_ms = -1;
};

// How the peak memory is measured (for reports).
std::string peak_memory_method();

// Runs every (setting, module); `progress` is called after each with the result so far.
std::vector<ModuleCost> benchmark_modules(const ModelBenchOptions& options,
                                          const std::function<void(const ModuleCost&)>& progress = {});

}  // namespace phyir::model
