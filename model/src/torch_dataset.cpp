// The dataset's manifest as a torch::data dataset: views listed by find_view_folders (the
// manifest's split, in manifest order), each loaded by load_view when the sampler asks.
#include "torch_dataset.h"

#include "data.h"
#include "phyir/core/error.h"

namespace fs = std::filesystem;

namespace phyir::model {

ExampleSize ExampleSize::of(const ModelConfig& c) {
  return {c.input_height, c.input_width, c.render_height, c.render_width, c.probe_height, c.probe_width};
}

ModelConfig ExampleSize::model_config() const {
  ModelConfig c;
  c.input_height = height;
  c.input_width = width;
  c.render_height = probe_grid_height;
  c.render_width = probe_grid_width;
  c.probe_height = probe_height;
  c.probe_width = probe_width;
  return c;
}

ManifestDataset::ManifestDataset(const fs::path& root, const std::string& split, ExampleSize size) : size_(size) {
  for (int v : {size.height, size.width, size.probe_grid_height, size.probe_grid_width, size.probe_height,
                size.probe_width})
    if (v <= 0) fail("dataset {}: every example size must be positive", root.string());
  // Without a manifest find_view_folders would scan folders: a dataset still being
  // generated has no manifest, and its half-done views must not be trained on.
  if (!fs::is_regular_file(root / "manifest.json"))
    fail("{}: no manifest.json (the dataset is not finished: run the same 'phyir dataset generate' command "
         "again, or 'phyir dataset merge' for shards)",
         (root / "manifest.json").string());
  folders_ = find_view_folders(root, split);
  for (const fs::path& f : folders_) ids_.push_back(fs::relative(f, root / "views").generic_string());
}

DatasetExample ManifestDataset::get(size_t index) {
  const fs::path& dir = folders_.at(index);
  const ModelConfig config = size_.model_config();
  ViewTensors v = load_view(dir, config);
  const auto mask_or_zeros = [&](const char* name) {
    torch::Tensor m = read_mask(dir / name, size_.height, size_.width);
    return m.defined() ? m : torch::zeros({1, size_.height, size_.width});
  };
  DatasetExample e;
  e.id = ids_[index];
  e.index = static_cast<int64_t>(index);
  e.exposure_stops = v.exposure.stops;
  e.image = std::move(v.image);
  e.depth = std::move(v.depth);
  e.normal = std::move(v.normal);
  e.base_color = std::move(v.base_color);
  e.roughness = std::move(v.roughness);
  e.metalness = std::move(v.metalness);
  e.mask_geometry = std::move(v.mask);
  e.mask_emissive = mask_or_zeros("mask_emissive.exr");
  e.mask_transparent = mask_or_zeros("mask_transparent.exr");
  e.color = std::move(v.color_lo);
  e.render_mask = std::move(v.render_mask);
  e.probes = std::move(v.probes);
  e.probe_mask = std::move(v.probe_mask);
  return e;
}

ExampleBatch collate(const std::vector<DatasetExample>& examples) {
  if (examples.empty()) fail("collate: no examples");
  const auto stack = [&](torch::Tensor DatasetExample::*member) {
    std::vector<torch::Tensor> parts;
    for (const DatasetExample& e : examples) {
      if (!(e.*member).defined()) return torch::Tensor();
      parts.push_back(e.*member);
    }
    return torch::stack(parts, 0);
  };
  ExampleBatch b;
  std::vector<int64_t> index;
  for (const DatasetExample& e : examples) {
    b.ids.push_back(e.id);
    index.push_back(e.index);
  }
  b.index = torch::tensor(index, torch::kLong);
  b.image = stack(&DatasetExample::image);
  b.depth = stack(&DatasetExample::depth);
  b.normal = stack(&DatasetExample::normal);
  b.base_color = stack(&DatasetExample::base_color);
  b.roughness = stack(&DatasetExample::roughness);
  b.metalness = stack(&DatasetExample::metalness);
  b.mask_geometry = stack(&DatasetExample::mask_geometry);
  b.mask_emissive = stack(&DatasetExample::mask_emissive);
  b.mask_transparent = stack(&DatasetExample::mask_transparent);
  b.color = stack(&DatasetExample::color);
  b.render_mask = stack(&DatasetExample::render_mask);
  b.probes = stack(&DatasetExample::probes);
  b.probe_mask = stack(&DatasetExample::probe_mask);
  return b;
}

}  // namespace phyir::model
