// Networks and checkpoints (checkpoint.h).
#include "checkpoint.h"

#include <ATen/CPUGeneratorImpl.h>

#include <mutex>

#include "exposure.h"
#include "phyir/core/atomic_file.h"
#include "phyir/core/error.h"

namespace fs = std::filesystem;
using nlohmann::json;

namespace phyir::model {

json config_to_json(const ModelConfig& c) {
  return {{"input_height", c.input_height},   {"input_width", c.input_width},
          {"render_height", c.render_height}, {"render_width", c.render_width},
          {"probe_height", c.probe_height},   {"probe_width", c.probe_width},
          {"diffuse_samples", c.diffuse_samples}, {"specular_samples", c.specular_samples},
          {"guided_radius", c.guided_radius}, {"width_divisor", c.width_divisor},
          {"lnet_head", c.lnet_head}, {"target_units", c.target_units}};
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
  c.target_units = j.value("target_units", std::string("input"));  // checkpoints before the switch
  return c;
}

json weights_to_json(const LossWeights& w) {
  return {{"base_color", w.base_color}, {"roughness", w.roughness}, {"metalness", w.metalness},
          {"depth", w.depth},           {"normal", w.normal},       {"gradient", w.gradient},
          {"probe", w.probe},           {"coherence", w.coherence}, {"render", w.render}};
}

LossWeights weights_from_json(const json& j) {
  return {j.at("base_color"), j.at("roughness"), j.at("metalness"), j.at("depth"), j.at("normal"),
          j.at("gradient"),   j.at("probe"),     j.at("coherence"), j.at("render")};
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
  target_radiance(c);  // an unknown unit fails here
}

Networks::Networks(const ModelConfig& c)
    : gmnet(c.width_divisor),
      lnet(c.probe_height, c.probe_width, c.width_divisor, c.lnet_head == "light"),
      gsnet(c.guided_radius) {}

void Networks::to(const torch::Device& device) {
  gmnet->to(device);
  lnet->to(device);
  gsnet->to(device);
}

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
  const fs::path tmp = temporary_sibling(path);
  archive.save_to(tmp.string());
  commit_file(tmp, path);
}

namespace {

json read_meta(torch::serialize::InputArchive& archive, const std::string& path) {
  c10::IValue v;
  if (!archive.try_read("meta", v) || !v.isString()) fail("{}: not a PhyIR checkpoint (no metadata)", path);
  return json::parse(v.toStringRef());
}

// c10 messages carry a C++ backtrace after their first line.
std::string first_line(const std::string& text) { return text.substr(0, text.find('\n')); }

}  // namespace


json load_checkpoint(const std::string& path, Networks* nets, torch::optim::Optimizer* opt, bool rng,
                     const torch::Device& device) {
  if (!fs::is_regular_file(path)) fail("{}: checkpoint not found", path);
  torch::serialize::InputArchive archive;
  try {
    archive.load_from(path, device);
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
    gen.set_state(state.cpu());
  }
  return meta;
}

ModelConfig read_checkpoint_config(const std::string& path) {
  return config_from_json(load_checkpoint(path, nullptr, nullptr, false).at("config"));
}

}  // namespace phyir::model
