#pragma once
// The three networks as one object, and checkpoints: metadata JSON (stage, configuration,
// where to resume, settings, schedule, best validation so far), every network, optionally
// Adam's state and torch's CPU generator. Written atomically. Private header (torch types).
#include <torch/torch.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "nets.h"
#include "phyir/model/training.h"

namespace phyir::model {

// Every network, whatever the stage, so one checkpoint carries the whole model.
struct Networks {
  explicit Networks(const ModelConfig& c);
  void to(const torch::Device& device);  // every parameter and buffer
  GMNet gmnet;
  LNet lnet;
  GSNet gsnet;
};

nlohmann::json config_to_json(const ModelConfig& config);
ModelConfig config_from_json(const nlohmann::json& j);
// Throws phyir::Error naming the bad value (resolutions the networks cannot take, ...).
void check_config(const ModelConfig& config);

nlohmann::json weights_to_json(const LossWeights& weights);
LossWeights weights_from_json(const nlohmann::json& j);

// Writes `path` through a temporary sibling and a rename, so a killed run never leaves a
// half-written checkpoint. `opt` may be null (best.pt: networks only).
void save_checkpoint(const std::filesystem::path& path, const nlohmann::json& meta, Networks& nets,
                     torch::optim::Optimizer* opt);

// Reads the metadata, and whichever of the networks, optimiser state and generator state is
// asked for; tensors land on `device` whatever device wrote them (the generator state stays
// the CPU generator's). Errors name the file and what does not fit.
nlohmann::json load_checkpoint(const std::string& path, Networks* nets, torch::optim::Optimizer* opt, bool rng,
                               const torch::Device& device = torch::kCPU);

ModelConfig read_checkpoint_config(const std::string& path);

}  // namespace phyir::model
