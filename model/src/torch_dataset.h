#pragma once
// A dataset written by `phyir dataset generate` (docs/dataset.md) as a LibTorch
// torch::data dataset: the manifest's views of one split, each loaded from its view folder
// on demand (load_view, data.h) at a chosen resolution. Private header (torch types).
//
//   ManifestDataset data("data", "train", ExampleSize{});
//   auto loader = torch::data::make_data_loader<torch::data::samplers::RandomSampler>(
//       std::move(data), torch::data::DataLoaderOptions().batch_size(8).workers(2));
//   for (std::vector<DatasetExample>& examples : *loader) { ExampleBatch b = collate(examples); ... }
#include <torch/torch.h>

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "phyir/model/training.h"

namespace phyir::model {

// The resolutions an example is resampled to (area averaging down, bilinear up). Maps:
// height x width; HDR colour and the probe grid: probe_grid_height x probe_grid_width; each
// probe: probe_height x probe_width texels. The defaults are ModelConfig's (the network's).
struct ExampleSize {
  int height = 128, width = 256;
  int probe_grid_height = 32, probe_grid_width = 64;
  int probe_height = 8, probe_width = 16;

  static ExampleSize of(const ModelConfig& config);
  ModelConfig model_config() const;
};

// One view. Maps are [C, height, width] float tensors; masks hold 0 or 1 (a mask pixel is 1
// only where every source pixel it covers is 1).
struct DatasetExample {
  std::string id;     // "room_0/v003"
  int64_t index = 0;  // position in the dataset (the sampler's index)
  double exposure_stops = 0.0;     // input.png's exposure (view.json; 0 without): color and probes
                                   // are absolute, x 2^exposure_stops puts them in the input's
                                   // units as `phyir train` uses them (exposure.h)
  torch::Tensor image;             // [3] the network's input (input.png, sRGB-encoded, [0,1])
  torch::Tensor depth;             // [1] metres, Euclidean (0 where nothing is seen)
  torch::Tensor normal;            // [3] world space, unit length
  torch::Tensor base_color;        // [3] linear [0,1]
  torch::Tensor roughness;         // [1] [0,1]
  torch::Tensor metalness;         // [1] [0,1]
  torch::Tensor mask_geometry;     // [1] a surface is seen
  torch::Tensor mask_emissive;     // [1] an emitter is seen
  torch::Tensor mask_transparent;  // [1] a transmissive surface is seen
  torch::Tensor color;             // [3, grid h, grid w] HDR radiance (color.exr), linear Rec.709
  torch::Tensor render_mask;       // [1, grid h, grid w] surface, not emissive, not transparent
  torch::Tensor probes;            // [grid h, grid w, probe h, probe w, 3]; undefined without probes
  torch::Tensor probe_mask;        // [1, grid h, grid w]; undefined without probes
};

class ManifestDataset : public torch::data::datasets::Dataset<ManifestDataset, DatasetExample> {
 public:
  // `root` holds manifest.json (a finished dataset, a shard or a merged one); `split` is
  // train, val or test ("" = every view). Throws phyir::Error naming the file when there is
  // no manifest or the split has no views.
  ManifestDataset(const std::filesystem::path& root, const std::string& split, ExampleSize size = {});

  DatasetExample get(size_t index) override;
  torch::optional<size_t> size() const override { return folders_.size(); }

  const std::vector<std::string>& ids() const { return ids_; }
  const std::filesystem::path& folder(size_t index) const { return folders_.at(index); }

 private:
  std::vector<std::filesystem::path> folders_;
  std::vector<std::string> ids_;
  ExampleSize size_;
};

// The examples of a DataLoader batch stacked along a new first dimension; probes and
// probe_mask stay undefined unless every example has them.
struct ExampleBatch {
  std::vector<std::string> ids;
  torch::Tensor index;  // [N] int64
  torch::Tensor image, depth, normal, base_color, roughness, metalness;
  torch::Tensor mask_geometry, mask_emissive, mask_transparent;
  torch::Tensor color, render_mask, probes, probe_mask;
};
ExampleBatch collate(const std::vector<DatasetExample>& examples);

}  // namespace phyir::model
