// phyir bench model: wall time and peak memory of each module (docs/model.md, "Cost").
#include "phyir/model/benchmark.h"

#include <malloc.h>
#include <sys/resource.h>

#include <chrono>
#include <fstream>
#include <limits>
#include <optional>
#include <sstream>

#include "host_memory.h"
#include "nets.h"
#include "phyir/core/error.h"
#include "phyir/core/log.h"
#include "phyir/model/training.h"
#include "render_layer.h"
#include "stage_loss.h"

namespace phyir::model {

namespace {

// A field of /proc/self/status in KiB (VmRSS, VmHWM), -1 if unreadable.
long status_kib(const std::string& key) {
  std::ifstream f("/proc/self/status");
  std::string line;
  while (std::getline(f, line))
    if (line.rfind(key + ":", 0) == 0) return std::stol(line.substr(key.size() + 1));
  return -1;
}

// Writing 5 to clear_refs resets VmHWM to the current resident size (Linux >= 4.0).
bool reset_peak() {
  std::ofstream f("/proc/self/clear_refs");
  f << "5";
  return static_cast<bool>(f);
}

struct Measure {
  double ms = -1, peak_mib = -1, cpu_ms = -1;
};

double cpu_ms_now() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return (u.ru_utime.tv_sec + u.ru_stime.tv_sec) * 1e3 + (u.ru_utime.tv_usec + u.ru_stime.tv_usec) * 1e-3;
}

// Best wall time of `repeats` runs after a warm-up (oneDNN builds its primitives on the first
// call of each shape), and the peak resident memory over all of them above the resident
// memory before (inputs and weights, allocated before, are not counted).
template <typename Fn>
Measure measure(Fn&& fn, int repeats) {
  malloc_trim(0);
  const long base = status_kib("VmRSS");
  const bool peak_ok = reset_peak();
  using clock = std::chrono::steady_clock;
  auto t0 = clock::now();
  double c0 = cpu_ms_now();
  fn();
  double best = std::chrono::duration<double, std::milli>(clock::now() - t0).count();
  double cpu = cpu_ms_now() - c0;
  // A slow module is timed once more only if that costs under ~20 s.
  const int n = best > 20000 ? 0 : best > 5000 ? 1 : repeats;
  if (n > 0) c0 = cpu_ms_now();
  for (int i = 0; i < n; ++i) {
    if (i == 0) best = std::numeric_limits<double>::infinity();
    t0 = clock::now();
    fn();
    best = std::min(best, std::chrono::duration<double, std::milli>(clock::now() - t0).count());
  }
  if (n > 0) cpu = (cpu_ms_now() - c0) / n;  // mean over the timed runs
  Measure m;
  m.ms = best;
  m.cpu_ms = cpu;
  if (peak_ok && base >= 0) m.peak_mib = static_cast<double>(status_kib("VmHWM") - base) / 1024.0;
  return m;
}

// One run, timed as it comes: what a process that runs the network once (`phyir infer`) pays,
// first-call costs included (oneDNN primitives, fresh memory pages, OpenMP threads).
template <typename Fn>
Measure measure_once(Fn&& fn) {
  using clock = std::chrono::steady_clock;
  const double c0 = cpu_ms_now();
  const auto t0 = clock::now();
  fn();
  Measure m;
  m.ms = std::chrono::duration<double, std::milli>(clock::now() - t0).count();
  m.cpu_ms = cpu_ms_now() - c0;
  return m;
}

struct Setting {
  std::string name;
  int Hi, Wi, Hr, Wr, h, w, nd, ns;
};

Setting setting_named(const std::string& name) {
  if (name == "default") return {name, 128, 256, 32, 64, 8, 16, 64, 32};
  if (name == "paper") return {name, 256, 512, 128, 256, 16, 32, 512, 256};
  fail("bench model: setting '{}': default or paper", name);
}

RenderSettings render_settings(const Setting& s) {
  RenderSettings rs;
  rs.diffuse_samples = s.nd;
  rs.specular_samples = s.ns;
  return rs;
}

// Full inference as `phyir infer` runs it (predict.cpp, stage_loss.cpp's run_light): GMNet,
// GSNet, LNet, rendering layer, no gradient.
// `inference_mode`: under c10::InferenceMode instead of a NoGradGuard (no version counters or
// view tracking; measured for inference.cpp, which uses the guard).
void full_inference(GMNet& gm, GSNet& gs, LNet& ln, const torch::Tensor& image, const Setting& s,
                    bool inference_mode = false) {
  torch::NoGradGuard ng;
  std::optional<c10::InferenceMode> im;
  if (inference_mode) im.emplace();
  const GMOutput g = gs->forward(image, gm->forward(image));
  const torch::Tensor lp = ln->forward(lnet_input(image, g, s.Hr, s.Wr));
  const auto area = [&](const torch::Tensor& x) {
    return torch::nn::functional::adaptive_avg_pool2d(
        x, torch::nn::functional::AdaptiveAvgPool2dFuncOptions({s.Hr, s.Wr}));
  };
  render_layer(normalize_channels(area(g.normal)), area(g.base_color), area(g.roughness), area(g.metalness), linear_probes(lp),
               render_settings(s));
}

torch::Tensor sum_of(const GMOutput& o) {
  return o.depth.sum() + o.normal.sum() + o.base_color.sum() + o.roughness.sum() + o.metalness.sum();
}

}  // namespace

std::string peak_memory_method() {
  return "peak resident memory (VmHWM of /proc/self/status, reset through /proc/self/clear_refs) "
         "above the resident memory just before the module runs (its inputs and weights excluded); "
         "malloc_trim before each module, so memory freed before it leaves the resident set "
         "(the commands keep freed memory for reuse: host_memory.h)";
}

std::vector<ModuleCost> benchmark_modules(const ModelBenchOptions& o,
                                          const std::function<void(const ModuleCost&)>& progress) {
  init_logging();
  // Bad names fail before minutes of measuring, not after.
  for (const std::string& name : o.settings) setting_named(name);
  for (const std::string& head : o.lnet_heads)
    if (head != "paper" && head != "light") fail("bench model: LNet head '{}': paper or light", head);
  if (o.threads < 1 || o.repeats < 0) fail("bench model: threads {} and repeats {}: at least 1 and 0", o.threads, o.repeats);
  set_threads(o.threads);
  retain_freed_memory();  // the commands' memory policy: timed as `phyir infer` runs
  std::vector<ModuleCost> out;
  auto report = [&](ModuleCost c) {
    out.push_back(c);
    if (progress) progress(out.back());
  };
  for (const std::string& sname : o.settings) {
    const Setting s = setting_named(sname);
    torch::manual_seed(static_cast<int64_t>(o.seed));
    const std::string in_shape = fmt::format("input {}x{}", s.Wi, s.Hi);
    const std::string render_shape =
        fmt::format("{}x{}, {}x{} probes, {}/{} samples", s.Wr, s.Hr, s.w, s.h, s.nd, s.ns);
    GMNet gm;
    GSNet gs(2);
    const torch::Tensor image = torch::rand({1, 3, s.Hi, s.Wi});
    if (!o.lnet_heads.empty()) {
      // First, before anything has run at these sizes: the first head's inference, once.
      const std::string& head = o.lnet_heads.front();
      LNet ln(s.h, s.w, 1, head == "light");
      gm->eval(), gs->eval(), ln->eval();
      ModuleCost c{sname, "inference", head + ", first call", in_shape + ", " + render_shape};
      const Measure m = measure_once([&] { full_inference(gm, gs, ln, image, s); });
      c.forward_ms = m.ms, c.forward_cpu_ms = m.cpu_ms;
      report(c);
    }
    GMOutput gm_out;
    {
      torch::NoGradGuard ng;
      gm->eval();
      gm_out = gm->forward(image);
    }
    // GMNet
    {
      ModuleCost c{sname, "gmnet", "", in_shape};
      {
        torch::NoGradGuard ng;
        gm->eval();
        const Measure m = measure([&] { gm->forward(image); }, o.repeats);
        c.forward_ms = m.ms, c.forward_peak_mib = m.peak_mib, c.forward_cpu_ms = m.cpu_ms;
      }
      if (o.backward) {
        gm->train();
        const Measure m = measure([&] {
          sum_of(gm->forward(image)).backward();
          gm->zero_grad();
        }, o.repeats);
        c.forward_backward_ms = m.ms, c.forward_backward_peak_mib = m.peak_mib, c.forward_backward_cpu_ms = m.cpu_ms;
        gm->eval();
      }
      report(c);
    }
    // GMNet's parts: the encoder, and the five decoders on its features.
    {
      torch::NoGradGuard ng;
      const torch::Tensor x = image * 2.0 - 1.0;  // as GMNet's forward
      ModuleCost e{sname, "gmnet_encoder", "", in_shape};
      const Measure me = measure([&] { gm->encoder->forward(x); }, o.repeats);
      e.forward_ms = me.ms, e.forward_peak_mib = me.peak_mib, e.forward_cpu_ms = me.cpu_ms;
      report(e);
      const std::vector<torch::Tensor> f = gm->encoder->forward(x);
      ModuleCost d{sname, "gmnet_decoders", "", "5 decoders, " + in_shape};
      const Measure md = measure([&] {
        for (Decoder* dec : {&gm->depth, &gm->normal, &gm->base_color, &gm->roughness, &gm->metalness})
          (*dec)->forward(f);
      }, o.repeats);
      d.forward_ms = md.ms, d.forward_peak_mib = md.peak_mib, d.forward_cpu_ms = md.cpu_ms;
      report(d);
    }
    // GSNet
    {
      ModuleCost c{sname, "gsnet", "", in_shape + " (filter at half resolution)"};
      {
        torch::NoGradGuard ng;
        gs->eval();
        const Measure m = measure([&] { gs->forward(image, gm_out); }, o.repeats);
        c.forward_ms = m.ms, c.forward_peak_mib = m.peak_mib, c.forward_cpu_ms = m.cpu_ms;
      }
      if (o.backward) {
        gs->train();
        const Measure m = measure([&] {
          sum_of(gs->forward(image, gm_out)).backward();
          gs->zero_grad();
        }, o.repeats);
        c.forward_backward_ms = m.ms, c.forward_backward_peak_mib = m.peak_mib, c.forward_backward_cpu_ms = m.cpu_ms;
        gs->eval();
      }
      report(c);
    }
    // Rendering layer: maps and probes at the rendering resolution.
    {
      ModuleCost c{sname, "render_layer", "", render_shape};
      RenderSettings rs;
      rs.diffuse_samples = s.nd;
      rs.specular_samples = s.ns;
      const torch::Tensor n = torch::nn::functional::normalize(
          torch::rand({1, 3, s.Hr, s.Wr}) - 0.5, torch::nn::functional::NormalizeFuncOptions().dim(1));
      const torch::Tensor B = torch::rand({1, 3, s.Hr, s.Wr}), R = torch::rand({1, 1, s.Hr, s.Wr}),
                          M = torch::rand({1, 1, s.Hr, s.Wr});
      const torch::Tensor probes = torch::rand({1, s.Hr, s.Wr, s.h, s.w, 3}) * 2.0;
      {
        torch::NoGradGuard ng;
        const Measure m = measure([&] { render_layer(n, B, R, M, probes, rs); }, o.repeats);
        c.forward_ms = m.ms, c.forward_peak_mib = m.peak_mib, c.forward_cpu_ms = m.cpu_ms;
      }
      if (o.backward) {
        // As in the joint stage: every input needs a gradient.
        std::vector<torch::Tensor> leaves;
        for (const torch::Tensor& t : {n, B, R, M, probes}) leaves.push_back(t.clone().set_requires_grad(true));
        const Measure m = measure([&] {
          render_layer(leaves[0], leaves[1], leaves[2], leaves[3], leaves[4], rs).image.sum().backward();
          for (auto& t : leaves) t.mutable_grad() = torch::Tensor();
        }, o.repeats);
        c.forward_backward_ms = m.ms, c.forward_backward_peak_mib = m.peak_mib, c.forward_backward_cpu_ms = m.cpu_ms;
      }
      report(c);
    }
    // LNet and full inference, once per head.
    for (const std::string& head : o.lnet_heads) {
      if (head != "paper" && head != "light") fail("bench model: LNet head '{}': paper or light", head);
      LNet ln(s.h, s.w, 1, head == "light");
      torch::Tensor in;
      {
        torch::NoGradGuard ng;
        in = lnet_input(image, gm_out, s.Hr, s.Wr);
      }
      ModuleCost c{sname, "lnet", head, fmt::format("{}x{}, {}x{} probes", s.Wr, s.Hr, s.w, s.h)};
      {
        torch::NoGradGuard ng;
        ln->eval();
        const Measure m = measure([&] { ln->forward(in); }, o.repeats);
        c.forward_ms = m.ms, c.forward_peak_mib = m.peak_mib, c.forward_cpu_ms = m.cpu_ms;
      }
      if (o.backward) {
        ln->train();
        const Measure m = measure([&] {
          ln->forward(in).sum().backward();
          ln->zero_grad();
        }, o.repeats);
        c.forward_backward_ms = m.ms, c.forward_backward_peak_mib = m.peak_mib, c.forward_backward_cpu_ms = m.cpu_ms;
        ln->eval();
      }
      report(c);
      // Full inference as `phyir infer` runs it, after the warm-up.
      ModuleCost f{sname, "inference", head, in_shape + ", " + render_shape};
      const Measure m = measure([&] { full_inference(gm, gs, ln, image, s); }, o.repeats);
      f.forward_ms = m.ms, f.forward_peak_mib = m.peak_mib, f.forward_cpu_ms = m.cpu_ms;
      report(f);
      if (head == o.lnet_heads.front()) {
        ModuleCost g = f;
        g.variant = head + ", InferenceMode";
        const Measure mi = measure([&] { full_inference(gm, gs, ln, image, s, true); }, o.repeats);
        g.forward_ms = mi.ms, g.forward_peak_mib = mi.peak_mib, g.forward_cpu_ms = mi.cpu_ms;
        report(g);
      }
    }
  }
  return out;
}

}  // namespace phyir::model
