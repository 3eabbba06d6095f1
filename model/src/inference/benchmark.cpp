// phyir bench model: wall time and peak memory of each module (docs/model-results.md, "Cost").
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
#include "phyir/core/log.h"
#include "phyir/core/setting_error.h"
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
  fail_setting("settings", "'{}' is not one of: default, paper", name);
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

void set_forward(ModuleCost& c, const Measure& m) {
  c.forward_ms = m.ms, c.forward_peak_mib = m.peak_mib, c.forward_cpu_ms = m.cpu_ms;
}
void set_forward_backward(ModuleCost& c, const Measure& m) {
  c.forward_backward_ms = m.ms, c.forward_backward_peak_mib = m.peak_mib, c.forward_backward_cpu_ms = m.cpu_ms;
}

void check_lnet_head(const std::string& head) {
  if (head != "paper" && head != "light") fail_setting("lnet_heads", "'{}' is not one of: paper, light", head);
}

// Bad values fail before minutes of measuring, not after.
void check_options(const ModelBenchOptions& o) {
  for (const std::string& name : o.settings) setting_named(name);
  for (const std::string& head : o.lnet_heads) check_lnet_head(head);
  if (o.threads < 1) fail_setting("threads", "{} must be at least 1", o.threads);
  if (o.repeats < 0) fail_setting("repeats", "{} must be >= 0", o.repeats);
}

// The modules of one setting, measured in this order (the weights and inputs are drawn from
// the seed in this order): inference's first call, GMNet and its parts, GSNet, the rendering
// layer, then LNet and full inference per head. Each result goes to `report` as it comes.
class SettingBench {
 public:
  using Report = std::function<void(const ModuleCost&)>;

  SettingBench(const ModelBenchOptions& o, const std::string& sname, const Report& report)
      : o_(o), sname_(sname), s_(setting_named(sname)), report_(report) {
    torch::manual_seed(static_cast<int64_t>(o.seed));
    in_shape_ = fmt::format("input {}x{}", s_.Wi, s_.Hi);
    render_shape_ = fmt::format("{}x{}, {}x{} probes, {}/{} samples", s_.Wr, s_.Hr, s_.w, s_.h, s_.nd, s_.ns);
    gm_ = GMNet();
    gs_ = GSNet(2);
    image_ = torch::rand({1, 3, s_.Hi, s_.Wi});
  }

  void run() {
    if (!o_.lnet_heads.empty()) first_inference();
    {
      torch::NoGradGuard ng;
      gm_->eval();
      gm_out_ = gm_->forward(image_);
    }
    gmnet();
    gmnet_parts();
    gsnet();
    rendering_layer();
    for (const std::string& head : o_.lnet_heads) lnet_and_inference(head);
  }

 private:
  // First, before anything has run at these sizes: the first head's inference, once.
  void first_inference() {
    const std::string& head = o_.lnet_heads.front();
    LNet ln(s_.h, s_.w, 1, head == "light");
    gm_->eval(), gs_->eval(), ln->eval();
    ModuleCost c{sname_, "inference", head + ", first call", in_shape_ + ", " + render_shape_};
    const Measure m = measure_once([&] { full_inference(gm_, gs_, ln, image_, s_); });
    c.forward_ms = m.ms, c.forward_cpu_ms = m.cpu_ms;
    report_(c);
  }

  // Forward in eval mode without gradient; with o.backward, forward + backward (`train_step`)
  // in training mode too. Leaves `net` in eval mode.
  template <typename Net, typename Forward, typename TrainStep>
  void time_net(ModuleCost& c, Net& net, const Forward& forward, const TrainStep& train_step) {
    {
      torch::NoGradGuard ng;
      net->eval();
      set_forward(c, measure(forward, o_.repeats));
    }
    if (o_.backward) {
      net->train();
      set_forward_backward(c, measure([&] {
        train_step();
        net->zero_grad();
      }, o_.repeats));
      net->eval();
    }
  }

  void gmnet() {
    ModuleCost c{sname_, "gmnet", "", in_shape_};
    time_net(c, gm_, [&] { gm_->forward(image_); }, [&] { sum_of(gm_->forward(image_)).backward(); });
    report_(c);
  }

  // GMNet's parts: the encoder, and the five decoders on its features.
  void gmnet_parts() {
    torch::NoGradGuard ng;
    const torch::Tensor x = image_ * 2.0 - 1.0;  // as GMNet's forward
    ModuleCost e{sname_, "gmnet_encoder", "", in_shape_};
    set_forward(e, measure([&] { gm_->encoder->forward(x); }, o_.repeats));
    report_(e);
    const std::vector<torch::Tensor> f = gm_->encoder->forward(x);
    ModuleCost d{sname_, "gmnet_decoders", "", "5 decoders, " + in_shape_};
    set_forward(d, measure([&] {
      for (Decoder* dec : {&gm_->depth, &gm_->normal, &gm_->base_color, &gm_->roughness, &gm_->metalness})
        (*dec)->forward(f);
    }, o_.repeats));
    report_(d);
  }

  void gsnet() {
    ModuleCost c{sname_, "gsnet", "", in_shape_ + " (filter at half resolution)"};
    time_net(c, gs_, [&] { gs_->forward(image_, gm_out_); },
             [&] { sum_of(gs_->forward(image_, gm_out_)).backward(); });
    report_(c);
  }

  // Rendering layer: maps and probes at the rendering resolution.
  void rendering_layer() {
    ModuleCost c{sname_, "render_layer", "", render_shape_};
    const RenderSettings rs = render_settings(s_);
    const torch::Tensor n = torch::nn::functional::normalize(
        torch::rand({1, 3, s_.Hr, s_.Wr}) - 0.5, torch::nn::functional::NormalizeFuncOptions().dim(1));
    const torch::Tensor B = torch::rand({1, 3, s_.Hr, s_.Wr}), R = torch::rand({1, 1, s_.Hr, s_.Wr}),
                        M = torch::rand({1, 1, s_.Hr, s_.Wr});
    const torch::Tensor probes = torch::rand({1, s_.Hr, s_.Wr, s_.h, s_.w, 3}) * 2.0;
    {
      torch::NoGradGuard ng;
      set_forward(c, measure([&] { render_layer(n, B, R, M, probes, rs); }, o_.repeats));
    }
    if (o_.backward) {
      // As in the joint stage: every input needs a gradient.
      std::vector<torch::Tensor> leaves;
      for (const torch::Tensor& t : {n, B, R, M, probes}) leaves.push_back(t.clone().set_requires_grad(true));
      set_forward_backward(c, measure([&] {
        render_layer(leaves[0], leaves[1], leaves[2], leaves[3], leaves[4], rs).image.sum().backward();
        for (auto& t : leaves) t.mutable_grad() = torch::Tensor();
      }, o_.repeats));
    }
    report_(c);
  }

  // LNet, then full inference as `phyir infer` runs it (after the warm-up); for the first head
  // also under InferenceMode.
  void lnet_and_inference(const std::string& head) {
    check_lnet_head(head);
    LNet ln(s_.h, s_.w, 1, head == "light");
    torch::Tensor in;
    {
      torch::NoGradGuard ng;
      in = lnet_input(image_, gm_out_, s_.Hr, s_.Wr);
    }
    ModuleCost c{sname_, "lnet", head, fmt::format("{}x{}, {}x{} probes", s_.Wr, s_.Hr, s_.w, s_.h)};
    time_net(c, ln, [&] { ln->forward(in); }, [&] { ln->forward(in).sum().backward(); });
    report_(c);
    ModuleCost f{sname_, "inference", head, in_shape_ + ", " + render_shape_};
    set_forward(f, measure([&] { full_inference(gm_, gs_, ln, image_, s_); }, o_.repeats));
    report_(f);
    if (head == o_.lnet_heads.front()) {
      ModuleCost g = f;
      g.variant = head + ", InferenceMode";
      set_forward(g, measure([&] { full_inference(gm_, gs_, ln, image_, s_, true); }, o_.repeats));
      report_(g);
    }
  }

  const ModelBenchOptions& o_;
  const std::string sname_;
  const Setting s_;
  const Report& report_;
  std::string in_shape_, render_shape_;
  GMNet gm_{nullptr};
  GSNet gs_{nullptr};
  torch::Tensor image_;
  GMOutput gm_out_;
};

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
  check_options(o);
  set_threads(o.threads);
  retain_freed_memory();  // the commands' memory policy: timed as `phyir infer` runs
  std::vector<ModuleCost> out;
  const SettingBench::Report report = [&](const ModuleCost& c) {
    out.push_back(c);
    if (progress) progress(out.back());
  };
  for (const std::string& sname : o.settings) SettingBench(o, sname, report).run();
  return out;
}

}  // namespace phyir::model
