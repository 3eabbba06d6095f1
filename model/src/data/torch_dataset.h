#pragma once
// A dataset's views as a LibTorch torch::data dataset: each view read from its folder when the
// sampler asks (load_view, data.h: the one reader, used by `phyir train` through
// view_stream.h), batches stacked by collate (data.h: the one batching). Private header
// (torch types).
//
//   ManifestDataset data("data", "train", ExampleSize{});
//   auto loader = torch::data::make_data_loader<torch::data::samplers::RandomSampler>(
//       std::move(data), torch::data::DataLoaderOptions().batch_size(8).workers(2));
//   for (std::vector<DatasetExample>& examples : *loader) { ExampleBatch b = collate(examples); ... }
#include <torch/torch.h>

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "data.h"
#include "exposure.h"
#include "phyir/model/training.h"
#include "view_census.h"

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

// One view (ViewTensors, data.h): maps [C, height, width]; `mask` is mask_geometry, `color_lo`
// the HDR colour on the probe grid, `exposure.stops` input.png's exposure; masks hold 0 or 1.
using DatasetExample = ViewTensors;
// Examples stacked along a new first dimension (collate, data.h).
using ExampleBatch = Batch;

class ManifestDataset : public torch::data::datasets::Dataset<ManifestDataset, ViewTensors> {
 public:
  // `root` holds manifest.json (a finished dataset, a shard or a merged one); `split` is
  // train, val or test ("" = every view). Radiance as the files hold it. Throws phyir::Error
  // naming the file when there is no manifest or the split has no views.
  ManifestDataset(const std::filesystem::path& root, const std::string& split, ExampleSize size = {});

  // What `phyir train` reads: the views of `split` (view::find_views: a manifest's split, or
  // without one every view folder below root), the first `max_views` (0: all), at
  // `config`'s resolutions, radiance in `units`; probes.exr read only `with_probes`.
  static ManifestDataset for_training(const std::filesystem::path& root, const std::string& split, int max_views,
                                      const ModelConfig& config, view::RadianceUnits units, bool with_probes = true);

  ViewTensors get(size_t index) override;
  torch::optional<size_t> size() const override { return views_.size(); }

  const std::vector<std::string>& ids() const { return ids_; }
  const std::filesystem::path& folder(size_t index) const { return views_.at(index).dir; }
  const ModelConfig& config() const { return config_; }

  // Counts every view get() decodes from now on (copies of the dataset share the census).
  void count_views(std::shared_ptr<ViewCensus> census) { census_ = std::move(census); }

 private:
  ManifestDataset(const std::filesystem::path& root, std::vector<view::ViewRecord> views, const ModelConfig& config,
                  view::RadianceUnits units);

  std::vector<view::ViewRecord> views_;
  std::vector<std::string> ids_;
  ModelConfig config_;
  view::RadianceUnits units_ = view::RadianceUnits::kAbsolute;
  bool with_probes_ = true;
  std::shared_ptr<ViewCensus> census_;
};

}  // namespace phyir::model
