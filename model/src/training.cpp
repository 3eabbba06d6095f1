// Staged training (appendix B.1), checkpoints with exact resume, inference.
#include "phyir/model/training.h"

#include <ATen/CPUGeneratorImpl.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>
#include <mutex>
#include <sstream>

#include "data.h"
#include "losses.h"
#include "nets.h"
#include "phyir/core/atomic_file.h"
#include "phyir/core/colour.h"
#include "phyir/core/error.h"
#include "phyir/core/image_io.h"
#include "phyir/core/log.h"
#include "render_layer.h"

namespace fs = std::filesystem;
using nlohmann::json;

namespace phyir::model {

// --- Stages and defaults ----------------------------------------------------------------------

Stage parse_stage(const std::string& name) {
  if (name == "gmnet") return Stage::kGMNet;
  if (name == "lnet") return Stage::kLNet;
  if (name == "joint") return Stage::kJoint;
  if (name == "gsnet") return Stage::kGSNet;
  fail("--stage '{}': expected gmnet, lnet, joint or gsnet", name);
}

std::string stage_name(Stage s) {
  switch (s) {
    case Stage::kGMNet: return "gmnet";
    case Stage::kLNet: return "lnet";
    case Stage::kJoint: return "joint";
    case Stage::kGSNet: return "gsnet";
  }
  return "?";
}

StageDefaults stage_defaults(Stage s) {
  StageDefaults d{};
  switch (s) {
    case Stage::kGMNet:  // B.1: 120 epochs, lr 1e-4, batch 8, beta_B,R,M,D = 1, beta_N,gradient = 0.1
      d = {1e-4, 8, 120, {}};
      d.weights.probe = d.weights.coherence = d.weights.render = 0.0;
      break;
    case Stage::kLNet:  // 90 epochs, lr 1e-4, batch 4, beta_L,SC,render = 1
      d = {1e-4, 4, 90, {}};
      d.weights.base_color = d.weights.roughness = d.weights.metalness = d.weights.depth = 0.0;
      d.weights.normal = d.weights.gradient = 0.0;
      break;
    case Stage::kJoint:  // 10 epochs, lr 1e-5, batch 4, beta_L,render = 1, beta_SC = 0.1 (+ GMNet's losses)
      d = {1e-5, 4, 10, {}};
      d.weights.coherence = 0.1;
      break;
    case Stage::kGSNet:  // 80 epochs, lr 5e-4, batch 16, beta_B,R = 1, beta_N = 0.1
      d = {5e-4, 16, 80, {}};
      d.weights.metalness = d.weights.depth = d.weights.gradient = 0.0;
      d.weights.probe = d.weights.coherence = d.weights.render = 0.0;
      break;
  }
  return d;
}

void set_threads(int threads) {
  torch::set_num_threads(std::max(1, threads));
}

namespace {

json config_to_json(const ModelConfig& c) {
  return {{"input_height", c.input_height},   {"input_width", c.input_width},
          {"render_height", c.render_height}, {"render_width", c.render_width},
          {"probe_height", c.probe_height},   {"probe_width", c.probe_width},
          {"diffuse_samples", c.diffuse_samples}, {"specular_samples", c.specular_samples},
          {"guided_radius", c.guided_radius}, {"width_divisor", c.width_divisor},
          {"lnet_head", c.lnet_head}};
}

ModelConfig config_from_json(const json& j) {
  ModelConfig c;
  c.input_height = j.at("input_height");
  c.input_width = j.at("input_width");
  c.render_height = j.at("render_height");
  c.render_width = j.at("render_width");
  c.probe_height = j.at("probe_height");
  c.probe_width = j.at("probe_width");
  c.diffuse_samples = j.at("diffuse_samples");
  c.specular_samples = j.at("specular_samples");
  c.guided_radius = j.at("guided_radius");
  c.width_divisor = j.value("width_divisor", 1);
  c.lnet_head = j.value("lnet_head", std::string("paper"));
  return c;
}

json weights_to_json(const LossWeights& w) {
  return {{"base_color", w.base_color}, {"roughness", w.roughness}, {"metalness", w.metalness},
          {"depth", w.depth},           {"normal", w.normal},       {"gradient", w.gradient},
          {"probe", w.probe},           {"coherence", w.coherence}, {"render", w.render}};
}

void check_config(const ModelConfig& c) {
  if (c.input_height <= 0 || c.input_height % 32 || c.input_width <= 0 || c.input_width % 32)
    fail("input resolution {}x{}: width and height must be positive multiples of 32 (ResNet-18)",
         c.input_width, c.input_height);
  if (c.render_height <= 0 || c.render_height % 16 || c.render_width <= 0 || c.render_width % 16)
    fail("rendering resolution {}x{}: width and height must be positive multiples of 16 (LNet)",
         c.render_width, c.render_height);
  if (c.probe_height < 2 || c.probe_width < 2) fail("probe size {}x{}: at least 2x2", c.probe_width, c.probe_height);
  if (c.diffuse_samples < 1 || c.specular_samples < 1) fail("sample counts must be at least 1");
  if (c.guided_radius < 1) fail("guided filter radius must be at least 1");
  if (c.width_divisor != 1 && c.width_divisor != 2 && c.width_divisor != 4)
    fail("width divisor {}: 1 (the paper's network), 2 or 4", c.width_divisor);
  if (c.lnet_head != "paper" && c.lnet_head != "light")
    fail("LNet head '{}': paper (appendix A.2) or light (docs/model.md)", c.lnet_head);
}

// Every network, whatever the stage, so one checkpoint carries the whole model.
struct Networks {
  explicit Networks(const ModelConfig& c)
      : gmnet(c.width_divisor), lnet(c.probe_height, c.probe_width, c.width_divisor, c.lnet_head == "light"), gsnet(c.guided_radius) {}
  GMNet gmnet;
  LNet lnet;
  GSNet gsnet;
};

void save_checkpoint(const fs::path& path, const json& meta, Networks& nets, torch::optim::Optimizer* opt) {
  torch::serialize::OutputArchive archive;
  archive.write("meta", c10::IValue(meta.dump()));
  for (auto [name, module] : std::vector<std::pair<std::string, torch::nn::Module*>>{
           {"gmnet", nets.gmnet.get()}, {"lnet", nets.lnet.get()}, {"gsnet", nets.gsnet.get()}}) {
    torch::serialize::OutputArchive sub;
    module->save(sub);
    archive.write(name, sub);
  }
  if (opt) {
    torch::serialize::OutputArchive sub;
    opt->save(sub);
    archive.write("optimizer", sub);
  }
  archive.write("rng", at::detail::getDefaultCPUGenerator().get_state());
  const fs::path tmp = path.string() + ".tmp";
  archive.save_to(tmp.string());
  fs::rename(tmp, path);
}

json read_meta(torch::serialize::InputArchive& archive, const std::string& path) {
  c10::IValue v;
  if (!archive.try_read("meta", v) || !v.isString()) fail("{}: not a PhyIR checkpoint (no metadata)", path);
  return json::parse(v.toStringRef());
}

// Loads networks (and optionally the optimiser and RNG state) from a checkpoint.
// c10 messages carry a C++ backtrace after their first line.
std::string first_line(const std::string& text) { return text.substr(0, text.find('\n')); }

json load_checkpoint(const std::string& path, Networks* nets, torch::optim::Optimizer* opt, bool rng) {
  if (!fs::is_regular_file(path)) fail("{}: checkpoint not found", path);
  torch::serialize::InputArchive archive;
  try {
    archive.load_from(path);
  } catch (const std::exception& e) {
    fail("{}: cannot read the checkpoint ({})", path, e.what());
  }
  json meta = read_meta(archive, path);
  if (nets) {
    for (auto [name, module] : std::vector<std::pair<std::string, torch::nn::Module*>>{
             {"gmnet", nets->gmnet.get()}, {"lnet", nets->lnet.get()}, {"gsnet", nets->gsnet.get()}}) {
      torch::serialize::InputArchive sub;
      if (!archive.try_read(name, sub)) fail("{}: no '{}' network", path, name);
      try {
        module->load(sub);
      } catch (const std::exception& e) {
        fail("{}: its '{}' network does not fit this configuration ({})", path, name, first_line(e.what()));
      }
    }
  }
  if (opt) {
    torch::serialize::InputArchive sub;
    if (!archive.try_read("optimizer", sub)) fail("{}: no optimiser state to resume from", path);
    try {
      opt->load(sub);
    } catch (const std::exception& e) {
      fail("{}: its optimiser state does not fit this stage ({})", path, first_line(e.what()));
    }
  }
  if (rng) {
    torch::Tensor state;
    if (!archive.try_read("rng", state)) fail("{}: no random-generator state to resume from", path);
    at::Generator gen = at::detail::getDefaultCPUGenerator();  // a handle on the shared generator
    std::lock_guard<std::mutex> lock(gen.mutex());
    gen.set_state(state);
  }
  return meta;
}

ModelConfig read_checkpoint_config(const std::string& path) {
  return config_from_json(load_checkpoint(path, nullptr, nullptr, false).at("config"));
}

// Named loss components of one step.
struct StepLoss {
  torch::Tensor total;
  std::vector<std::pair<std::string, torch::Tensor>> parts;
  void add(const std::string& name, double weight, const torch::Tensor& value) {
    if (weight == 0.0) return;
    parts.emplace_back(name, value.detach());
    total = total.defined() ? total + weight * value : weight * value;
  }
};

torch::Tensor area(const torch::Tensor& x, int h, int w) { return resize(x, h, w); }

void add_gm_losses(StepLoss& L, const LossWeights& w, const GMOutput& p, const Batch& b) {
  L.add("basecolor", w.base_color, l2_loss(p.base_color, b.base_color, b.mask));
  L.add("roughness", w.roughness, l2_loss(p.roughness, b.roughness, b.mask));
  L.add("metalness", w.metalness, metalness_loss(p.metalness, b.metalness, b.mask));
  L.add("depth", w.depth, berhu_loss(p.depth, b.depth, b.mask));
  L.add("normal", w.normal, normal_cosine_loss(p.normal, b.normal, b.mask));
  if (w.gradient != 0.0) {
    L.add("gradient", w.gradient,
          gradient_loss(p.base_color, b.base_color, b.mask) + gradient_loss(p.roughness, b.roughness, b.mask) +
              gradient_loss(p.normal, b.normal, b.mask) + gradient_loss(p.metalness, b.metalness, b.mask));
  }
}

struct LightResult {
  torch::Tensor log_probes;  // [B,Hr,Wr,h,w,3]
  RenderOutput render;
};

LightResult run_light(Networks& nets, const ModelConfig& c, const torch::Tensor& image, const GMOutput& gm) {
  LightResult r;
  const int Hr = c.render_height, Wr = c.render_width;
  r.log_probes = nets.lnet->forward(lnet_input(image, gm, Hr, Wr));
  const torch::Tensor probes = torch::expm1(r.log_probes.clamp_max(30.0));
  RenderSettings rs;
  rs.diffuse_samples = c.diffuse_samples;
  rs.specular_samples = c.specular_samples;
  r.render = render_layer(
      torch::nn::functional::normalize(area(gm.normal, Hr, Wr),
                                       torch::nn::functional::NormalizeFuncOptions().dim(1).eps(1e-6)),
      area(gm.base_color, Hr, Wr), area(gm.roughness, Hr, Wr), area(gm.metalness, Hr, Wr), probes, rs);
  return r;
}

void add_light_losses(StepLoss& L, const LossWeights& w, const ModelConfig& c, const LightResult& r,
                      const GMOutput& gm, const Batch& b) {
  if (!b.probes.defined()) fail("stage needs probes: a view folder has no probes.exr");
  L.add("probe", w.probe, probe_ssim_loss(r.log_probes, torch::log1p(b.probes), b.probe_mask));
  if (w.coherence != 0.0)
    L.add("coherence", w.coherence,
          spatial_coherence_loss(r.log_probes, area(gm.depth, c.render_height, c.render_width), b.render_mask));
  L.add("render", w.render, l2_loss(r.render.image, b.color_lo, b.render_mask));
}

std::string format_parts(const StepLoss& L) {
  std::string s;
  for (const auto& [name, v] : L.parts) s += fmt::format("{}{} {:.5g}", s.empty() ? "" : ", ", name, v.item<double>());
  return s;
}

}  // namespace

// --- Training ---------------------------------------------------------------------------------

TrainSummary train(const TrainOptions& o) {
  init_logging();
  set_threads(o.threads);
  const Stage stage = o.stage;
  const std::string sname = stage_name(stage);
  const StageDefaults defaults = stage_defaults(stage);
  if (o.epochs < 1) fail("--epochs {}: must be at least 1", o.epochs);
  if (o.out_dir.empty()) fail("--out: an output folder is required");
  const fs::path out(o.out_dir);
  fs::create_directories(out);
  const fs::path ckpt_path = out / "checkpoint.pt";
  if (o.resume && !fs::is_regular_file(ckpt_path)) fail("--resume: {} not found", ckpt_path.string());
  // A resumed run keeps its learning rate, batch size and weights unless they are given again.
  const json resumed = o.resume ? load_checkpoint(ckpt_path.string(), nullptr, nullptr, false) : json();
  // Before any state is loaded: another stage's optimiser has other parameter groups.
  if (o.resume && resumed.value("stage", std::string()) != sname)
    fail("--resume: {} is a '{}' checkpoint, not '{}' (start the stage with --init {} instead)", ckpt_path.string(),
         resumed.value("stage", std::string("?")), sname, ckpt_path.string());
  const double lr = o.learning_rate > 0 ? o.learning_rate
                    : o.resume           ? resumed.at("learning_rate").get<double>()
                                         : defaults.learning_rate;
  const int batch_size = o.batch_size > 0 ? o.batch_size
                         : o.resume       ? resumed.at("batch_size").get<int>()
                                          : defaults.batch_size;
  LossWeights w = o.custom_weights ? o.weights : defaults.weights;
  if (o.resume && !o.custom_weights) {
    const json& jw = resumed.at("weights");
    w = {jw.at("base_color"), jw.at("roughness"), jw.at("metalness"), jw.at("depth"), jw.at("normal"),
         jw.at("gradient"),   jw.at("probe"),     jw.at("coherence"), jw.at("render")};
  }

  // The configuration: from the checkpoint being resumed or initialised from, else the options.
  ModelConfig cfg = o.config;
  if (o.resume) cfg = read_checkpoint_config(ckpt_path.string());
  else if (!o.init.empty()) cfg = read_checkpoint_config(o.init);
  check_config(cfg);

  torch::manual_seed(o.seed);
  Networks nets(cfg);
  json trained = json::object({{"gmnet", false}, {"lnet", false}, {"gsnet", false}});
  if (!o.init.empty() && !o.resume) {
    const json meta = load_checkpoint(o.init, &nets, nullptr, false);
    trained = meta.value("trained", trained);
  }
  if (!o.encoder_weights.empty() && !o.resume && o.init.empty()) nets.gmnet->load_encoder(o.encoder_weights);

  // Which networks this stage trains; the others are frozen (eval mode, no gradients).
  const bool train_gm = stage == Stage::kGMNet || stage == Stage::kJoint;
  const bool train_l = stage == Stage::kLNet || stage == Stage::kJoint;
  const bool train_gs = stage == Stage::kGSNet;
  if ((stage == Stage::kLNet || stage == Stage::kGSNet) && !trained.value("gmnet", false))
    spdlog::warn("stage {}: GMNet is frozen but untrained (pass --init with a gmnet checkpoint)", sname);
  std::vector<torch::Tensor> params;
  auto collect = [&](torch::nn::Module& m, bool on) {
    for (auto& p : m.parameters()) {
      p.set_requires_grad(on);
      if (on) params.push_back(p);
    }
  };
  collect(*nets.gmnet, train_gm);
  collect(*nets.lnet, train_l);
  collect(*nets.gsnet, train_gs);
  torch::optim::Adam opt(params, torch::optim::AdamOptions(lr));

  int start_epoch = 0;
  int64_t start_batch = 0, global_step = 0;
  if (o.resume) {
    const json meta = load_checkpoint(ckpt_path.string(), &nets, &opt, true);
    if (meta.at("stage") != sname)
      fail("--resume: {} is a '{}' checkpoint, not '{}'", ckpt_path.string(), meta.at("stage").get<std::string>(), sname);
    for (auto& group : opt.param_groups()) static_cast<torch::optim::AdamOptions&>(group.options()).lr(lr);
    start_epoch = meta.at("epoch");
    start_batch = meta.at("batch");
    global_step = meta.at("global_step");
    trained = meta.at("trained");
  }

  // Data, loaded once at the network's resolutions.
  std::vector<fs::path> folders = find_view_folders(o.data_dir, o.split);
  if (o.max_views > 0 && folders.size() > static_cast<size_t>(o.max_views)) folders.resize(o.max_views);
  std::vector<ViewTensors> views;
  for (const auto& f : folders) views.push_back(load_view(f, cfg));
  if ((train_l) && !views.front().probes.defined())
    fail("stage {}: {} has no probes.exr (render the dataset with probes)", sname, folders.front().string());
  const int64_t n_views = static_cast<int64_t>(views.size());
  const int64_t bs = std::min<int64_t>(batch_size, n_views);
  const int64_t batches_per_epoch = (n_views + bs - 1) / bs;
  spdlog::info("train {}: {} views, batch {}, {} steps/epoch, lr {}, {} threads, input {}x{}, render {}x{}, probes {}x{}",
               sname, n_views, bs, batches_per_epoch, lr, o.threads, cfg.input_width, cfg.input_height,
               cfg.render_width, cfg.render_height, cfg.probe_width, cfg.probe_height);

  // Log: CSV with one row per step (rows past the resumed step are dropped) and a JSON summary.
  const fs::path csv_path = out / "train_log.csv";
  std::vector<std::string> kept;
  if (o.resume && fs::is_regular_file(csv_path)) {
    std::ifstream in(csv_path);
    std::string line;
    for (int i = 0; std::getline(in, line); ++i) {
      if (i == 0) { kept.push_back(line); continue; }
      std::istringstream row(line);
      std::string st, ep, gs;
      std::getline(row, st, ',');
      std::getline(row, ep, ',');
      std::getline(row, gs, ',');
      if (!gs.empty() && std::stoll(gs) <= global_step) kept.push_back(line);
    }
  }
  std::ofstream csv(csv_path, std::ios::trunc);
  if (!csv) fail("{}: cannot write", csv_path.string());
  bool header_written = !kept.empty();
  for (const auto& l : kept) csv << l << "\n";

  auto set_modes = [&](bool training) {
    nets.gmnet->train(training && train_gm);
    nets.lnet->train(training && train_l);
    nets.gsnet->train(training && train_gs);
  };

  TrainSummary summary;
  summary.checkpoint = ckpt_path.string();
  auto meta_now = [&](int epoch, int64_t batch) {
    json t = trained;
    if (train_gm) t["gmnet"] = true;
    if (train_l) t["lnet"] = true;
    if (train_gs) t["gsnet"] = true;
    return json{{"format", "phyir-checkpoint-1"}, {"stage", sname}, {"config", config_to_json(cfg)},
                {"epoch", epoch}, {"batch", batch}, {"global_step", global_step}, {"seed", o.seed},
                {"learning_rate", lr}, {"batch_size", bs}, {"weights", weights_to_json(w)}, {"trained", t}};
  };

  const auto t_start = std::chrono::steady_clock::now();
  bool stop = false;
  for (int epoch = start_epoch; epoch < o.epochs && !stop; ++epoch) {
    // The epoch's order depends only on (seed, epoch), so a resumed run sees the same batches.
    std::vector<size_t> order(views.size());
    for (size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::mt19937_64 shuffle_rng(o.seed * 1000003ULL + static_cast<uint64_t>(epoch));
    std::shuffle(order.begin(), order.end(), shuffle_rng);
    double epoch_sum = 0.0;
    int64_t epoch_steps = 0;
    set_modes(true);
    for (int64_t bi = (epoch == start_epoch ? start_batch : 0); bi < batches_per_epoch; ++bi) {
      const auto t0 = std::chrono::steady_clock::now();
      std::vector<size_t> idx(order.begin() + bi * bs, order.begin() + std::min<int64_t>((bi + 1) * bs, n_views));
      const Batch b = make_batch(views, idx);
      StepLoss L;
      GMOutput gm;
      if (train_gm) {
        gm = nets.gmnet->forward(b.image);
      } else {
        torch::NoGradGuard no_grad;
        gm = nets.gmnet->forward(b.image);
      }
      if (train_gm) add_gm_losses(L, w, gm, b);
      if (train_l) add_light_losses(L, w, cfg, run_light(nets, cfg, b.image, gm), gm, b);
      if (train_gs) {
        const GMOutput refined = nets.gsnet->forward(b.image, gm);
        L.add("basecolor", w.base_color, l2_loss(refined.base_color, b.base_color, b.mask));
        L.add("roughness", w.roughness, l2_loss(refined.roughness, b.roughness, b.mask));
        L.add("normal", w.normal, normal_cosine_loss(refined.normal, b.normal, b.mask));
      }
      if (!L.total.defined()) fail("stage {}: every loss weight is 0", sname);
      const double loss = L.total.item<double>();
      // The NaN check of every step: stop before the optimiser spreads it into the weights.
      if (!std::isfinite(loss))
        fail("train {}: the loss is {} at epoch {} step {} (global step {}): {}. Stopped; the last good "
             "checkpoint is {} (try a lower --lr)",
             sname, loss, epoch + 1, bi + 1, global_step + 1, format_parts(L), ckpt_path.string());
      opt.zero_grad();
      L.total.backward();
      opt.step();
      ++global_step;
      epoch_sum += loss;
      ++epoch_steps;
      const double dt = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_start).count();
      if (!header_written) {
        csv << "stage,epoch,global_step,loss";
        for (const auto& [name, v] : L.parts) csv << "," << name;
        csv << ",lr,seconds\n";
        header_written = true;
      }
      csv << sname << "," << epoch + 1 << "," << global_step << "," << fmt::format("{:.9g}", loss);
      for (const auto& [name, v] : L.parts) csv << "," << fmt::format("{:.9g}", v.item<double>());
      csv << "," << lr << "," << fmt::format("{:.3f}", elapsed) << "\n";
      csv.flush();
      if (o.progress)
        spdlog::info("[{}] epoch {}/{} step {}/{} loss {:.5g} ({}) {:.2f} s/step", sname, epoch + 1, o.epochs,
                     bi + 1, batches_per_epoch, loss, format_parts(L), dt);
      const bool at_limit = o.max_steps > 0 && global_step >= o.max_steps;
      const bool last_in_epoch = bi + 1 == batches_per_epoch;
      if (at_limit || (o.checkpoint_every > 0 && global_step % o.checkpoint_every == 0 && !last_in_epoch)) {
        // Resume point: the next batch of this epoch (or the next epoch).
        save_checkpoint(ckpt_path, last_in_epoch ? meta_now(epoch + 1, 0) : meta_now(epoch, bi + 1), nets, &opt);
      }
      if (at_limit) {
        stop = true;
        break;
      }
    }
    if (epoch_steps > 0) summary.epoch_losses.push_back(epoch_sum / static_cast<double>(epoch_steps));
    if (!stop) {
      save_checkpoint(ckpt_path, meta_now(epoch + 1, 0), nets, &opt);
      summary.epochs_done = epoch + 1;
    }
  }
  csv.close();
  summary.steps = global_step;
  if (!summary.epoch_losses.empty()) {
    summary.first_loss = summary.epoch_losses.front();
    summary.last_loss = summary.epoch_losses.back();
  }
  if (!fs::is_regular_file(ckpt_path)) save_checkpoint(ckpt_path, meta_now(start_epoch, start_batch), nets, &opt);

  json log = meta_now(summary.epochs_done, 0);
  log["epochs"] = o.epochs;
  log["paper_epochs"] = defaults.paper_epochs;
  log["threads"] = o.threads;
  log["views"] = n_views;
  log["epoch_mean_loss"] = summary.epoch_losses;
  log["seconds"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_start).count();
  std::ofstream(out / "train_log.json") << log.dump(2) << "\n";

  if (!o.plot_script.empty()) {
    const fs::path png = out / "loss_curve.png";
    const std::string cmd = fmt::format("/usr/bin/python3 '{}' '{}' '{}' > /dev/null 2>&1", o.plot_script,
                                        csv_path.string(), png.string());
    if (std::system(cmd.c_str()) == 0 && fs::is_regular_file(png)) summary.plot = png.string();
    else spdlog::warn("loss curve: {} failed (needs /usr/bin/python3 with matplotlib)", o.plot_script);
  }
  spdlog::info("train {}: {} steps, mean loss first epoch {:.5g}, last epoch {:.5g}; checkpoint {}", sname,
               summary.steps, summary.first_loss, summary.last_loss, ckpt_path.string());
  return summary;
}

// --- Inference --------------------------------------------------------------------------------

void infer(const InferOptions& o) {
  init_logging();
  set_threads(o.threads);
  torch::manual_seed(o.seed);
  const ModelConfig cfg = read_checkpoint_config(o.checkpoint);
  Networks nets(cfg);
  const json meta = load_checkpoint(o.checkpoint, &nets, nullptr, false);
  nets.gmnet->eval();
  nets.lnet->eval();
  nets.gsnet->eval();
  torch::NoGradGuard no_grad;

  const fs::path in(o.input);
  if (!fs::is_regular_file(in)) fail("{}: input panorama not found", o.input);
  std::string ext = in.extension().string();
  for (auto& ch : ext) ch = static_cast<char>(std::tolower(ch));
  phyir::Image img = read_image(in);
  if (ext == ".exr" || ext == ".hdr") img = linear_to_display(img, static_cast<float>(o.exposure), "Standard");
  torch::Tensor x = image_to_tensor(img);
  if (x.size(0) == 1) x = x.expand({3, x.size(1), x.size(2)});
  x = x.narrow(0, 0, 3).unsqueeze(0).contiguous();
  if (x.size(3) != 2 * x.size(2))
    spdlog::warn("{}: {}x{} is not a 2:1 equirect panorama", o.input, x.size(3), x.size(2));
  const torch::Tensor panorama = x.clamp(0.0, 1.0);
  const int Hp = static_cast<int>(x.size(2)), Wp = static_cast<int>(x.size(3));
  x = resize(x, cfg.input_height, cfg.input_width).clamp(0.0, 1.0);

  const auto t0 = std::chrono::steady_clock::now();
  GMOutput gm = nets.gmnet->forward(x);
  const auto t1 = std::chrono::steady_clock::now();
  const bool use_gs = meta.at("trained").value("gsnet", false);
  if (use_gs) gm = nets.gsnet->forward(x, gm);
  const auto t2 = std::chrono::steady_clock::now();
  const LightResult light = run_light(nets, cfg, x, gm);
  const auto t3 = std::chrono::steady_clock::now();

  const fs::path out(o.out_dir);
  fs::create_directories(out);
  // Maps at the panorama's resolution (bilinear up, area down), as the renderer writes its AOVs
  // at the colour's resolution; normals renormalised after the interpolation.
  auto full = [&](const torch::Tensor& m) { return resize(m, Hp, Wp); };
  const torch::Tensor normal_full = torch::nn::functional::normalize(
      full(gm.normal), torch::nn::functional::NormalizeFuncOptions().dim(1).eps(1e-6));
  write_tensor_image(out / "input.png", panorama[0]);
  write_tensor_image(out / "depth.exr", full(gm.depth)[0], {"Y"});
  write_tensor_image(out / "normal.exr", normal_full[0], {"X", "Y", "Z"});
  write_tensor_image(out / "basecolor.exr", full(gm.base_color).clamp(0.0, 1.0)[0], {"R", "G", "B"});
  write_tensor_image(out / "roughness.exr", full(gm.roughness).clamp(0.0, 1.0)[0], {"Y"});
  write_tensor_image(out / "metalness.exr", full(gm.metalness).clamp(0.0, 1.0)[0], {"Y"});
  write_tensor_image(out / "probes.exr", probes_to_mosaic(torch::expm1(light.log_probes))[0], {"R", "G", "B"});
  write_tensor_image(out / "probe_mask.exr", torch::ones({1, cfg.render_height, cfg.render_width}), {"Y"});
  write_tensor_image(out / "rerender.exr", light.render.image[0], {"R", "G", "B"});
  auto ms = [](auto a, auto b) { return std::chrono::duration<double, std::milli>(b - a).count(); };
  json info = {{"checkpoint", o.checkpoint}, {"input", o.input}, {"config", config_to_json(cfg)},
               {"maps_resolution", {Wp, Hp}}, {"network_input_resolution", {cfg.input_width, cfg.input_height}},
               {"probe_grid", {cfg.render_width, cfg.render_height}},
               {"trained", meta.at("trained")}, {"guided_filter_applied", use_gs},
               {"conventions", {{"equirect", "row 0 = +Y, centre column = -Z, u = 0.5 + atan2(x,-z)/2pi, v = acos(y)/pi"},
                                {"depth", "Euclidean distance, metres"}, {"normal", "world space, unit"},
                                {"probes", "mosaic: probe (i,j) is the h x w world-oriented equirect block at row i*h, col j*w"}}},
               {"timings_ms", {{"gmnet", ms(t0, t1)}, {"gsnet", ms(t1, t2)}, {"lnet_and_render", ms(t2, t3)}}}};
  write_file_atomic(out / "infer.json", info.dump(2) + "\n");
  for (const char* m : {"gmnet", "lnet", "gsnet"})
    if (!meta.at("trained").value(m, false)) spdlog::warn("{}: {} was never trained (random weights)", o.checkpoint, m);
  spdlog::info("infer: wrote {} (GMNet {:.0f} ms, GSNet {:.0f} ms, LNet + rendering {:.0f} ms)", out.string(),
               ms(t0, t1), ms(t1, t2), ms(t2, t3));
}

// --- Rendering layer on ground truth -----------------------------------------------------------

RenderCheckResult check_render_layer(const RenderCheckOptions& o) {
  init_logging();
  set_threads(o.threads);
  torch::manual_seed(o.seed);
  torch::NoGradGuard no_grad;
  const fs::path dir(o.view_dir);
  const phyir::Image pmask_img = read_image(dir / "probe_mask.exr");
  const phyir::Image mosaic_img = read_image(dir / "probes.exr");
  const int gh = pmask_img.height, gw = pmask_img.width;
  if (mosaic_img.height % gh || mosaic_img.width % gw)
    fail("{}: {}x{} is not a grid of {}x{} probes", (dir / "probes.exr").string(), mosaic_img.width,
         mosaic_img.height, gw, gh);
  ModelConfig c;
  c.render_height = gh;
  c.render_width = gw;
  c.probe_height = mosaic_img.height / gh;
  c.probe_width = mosaic_img.width / gw;
  const phyir::Image color_img = read_image(dir / "color.exr");
  c.input_height = color_img.height;
  c.input_width = color_img.width;
  const ViewTensors v = load_view(dir, c);
  auto lo = [&](const torch::Tensor& x) { return resize(x.unsqueeze(0), gh, gw); };
  RenderSettings rs;
  rs.diffuse_samples = o.diffuse_samples;
  rs.specular_samples = o.specular_samples;
  const torch::Tensor normal = torch::nn::functional::normalize(
      lo(v.normal), torch::nn::functional::NormalizeFuncOptions().dim(1).eps(1e-6));
  const RenderOutput r = render_layer(normal, lo(v.base_color), lo(v.roughness), lo(v.metalness),
                                      v.probes.unsqueeze(0), rs);
  const torch::Tensor mask = (v.render_mask * v.probe_mask).unsqueeze(0).to(torch::kDouble);  // [1,1,H,W]
  const torch::Tensor I = v.color_lo.unsqueeze(0).to(torch::kDouble), Ir = r.image.to(torch::kDouble);
  const double n = mask.sum().item<double>() * 3.0;
  RenderCheckResult res;
  res.width = gw;
  res.height = gh;
  res.pixels = static_cast<int64_t>(mask.sum().item<double>());
  if (n > 0) {
    res.mse = ((I - Ir).square() * mask).sum().item<double>() / n;
    res.relative_mse = ((I - Ir).square() * mask).sum().item<double>() / (I.square() * mask).sum().item<double>();
    res.mean_color = (I * mask).sum().item<double>() / n;
    res.mean_rerender = (Ir * mask).sum().item<double>() / n;
    res.mean_abs_error = ((I - Ir).abs() * mask).sum().item<double>() / n;
  }
  if (!o.out_dir.empty()) {
    const fs::path out(o.out_dir);
    fs::create_directories(out);
    write_tensor_image(out / "rerender.exr", r.image[0], {"R", "G", "B"});
    write_tensor_image(out / "rerender_diffuse.exr", r.diffuse[0], {"R", "G", "B"});
    write_tensor_image(out / "rerender_specular.exr", r.specular[0], {"R", "G", "B"});
    write_tensor_image(out / "compare_mask.exr", mask[0].to(torch::kFloat), {"Y"});
    const json j = {{"view", o.view_dir}, {"width", gw}, {"height", gh}, {"probe_width", c.probe_width},
                    {"probe_height", c.probe_height}, {"diffuse_samples", o.diffuse_samples},
                    {"specular_samples", o.specular_samples}, {"pixels", res.pixels}, {"mse", res.mse},
                    {"relative_mse", res.relative_mse}, {"mean_color", res.mean_color},
                    {"mean_rerender", res.mean_rerender}, {"mean_abs_error", res.mean_abs_error}};
    std::ofstream(out / "check.json") << j.dump(2) << "\n";
  }
  return res;
}

}  // namespace phyir::model
