#pragma once
// Training data: one view (view/view_record.h: a dataset's or `phyir render`'s folder) turned
// into tensors at the network's resolutions (load_view: the one reader, under the torch::data
// dataset of torch_dataset.h), and views stacked into a batch (collate: the one batching).
// Private header.
#include <torch/torch.h>

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "exposure.h"
#include "phyir/core/image.h"
#include "phyir/model/training.h"
#include "phyir/view/probe_layout.h"
#include "phyir/view/view_record.h"

namespace phyir::model {

// One view at the network's resolutions. Input-resolution maps are [C, Hi, Wi]; rendering-
// resolution ones [C, Hr, Wr]; probes [Hr, Wr, h, w, 3] linear radiance (in the unit load_view
// was asked for: exposure.h).
struct ViewTensors {
  std::string name;          // the folder's name
  std::string id;            // its path in the dataset ("room_0/v003"); set by the dataset
  int64_t index = 0;         // its position in the dataset (the sampler's index); set by the dataset
  view::InputExposure exposure;    // input.png's, from view.json
  torch::Tensor image;       // LDR input (input.png, sRGB-encoded, [0,1])
  torch::Tensor depth, normal, base_color, roughness, metalness;
  torch::Tensor mask;        // 1 where a surface is seen (mask_geometry)
  torch::Tensor mask_emissive, mask_transparent;  // input resolution; zeros without the file
  torch::Tensor color_lo;    // HDR colour (color.exr) at the rendering resolution
  torch::Tensor render_mask; // surface, not emissive, not transparent, at the rendering resolution
  torch::Tensor probes;      // undefined when the view has no probes.exr
  torch::Tensor probe_mask;  // [1, Hr, Wr]
  // [Hr, Wr, h, w, 1]: each probe texel's standard error (luminance, the probes' unit);
  // undefined when the view has no probe_stderr.exr.
  torch::Tensor probe_stderr;
  // Held while the view's tensors live when a ViewCensus counts decoded views (view_census.h).
  std::shared_ptr<const void> census;
};

// Views stacked along a new first dimension, in the order given.
struct Batch {
  std::vector<std::string> ids;
  torch::Tensor index;  // [N] int64: the views' dataset indices
  torch::Tensor image, depth, normal, base_color, roughness, metalness, mask;
  torch::Tensor mask_emissive, mask_transparent;
  torch::Tensor color_lo, render_mask, probes, probe_mask;  // probes undefined if any view lacks them
  torch::Tensor probe_stderr;  // undefined if any view lacks it
  std::vector<std::string> without_probe_stderr;  // ids of the views with probes but no probe_stderr.exr
  std::vector<std::shared_ptr<const void>> census;          // the views' census tokens

  // Every tensor on `device` (a no-op on the CPU).
  Batch to(const torch::Device& device) const;
};

// One view at `config`'s resolutions, radiance (color_lo, probes) as the files hold it or in
// input units (x 2^exposure_stops of the record's input exposure): training asks for input
// units. `with_probes` false leaves probes.exr unread (probes and probe_mask undefined): the
// stages that train neither LNet nor the joint model never look at them, and at the paper's
// sizes they are 96% of a view (201 of 210 MB). The folder is record.dir (view/view_record.h).
ViewTensors load_view(const view::ViewRecord& record, const ModelConfig& config,
                      view::RadianceUnits radiance = view::RadianceUnits::kAbsolute, bool with_probes = true);
// The view in `folder` (view::read_view: its view.json when it has one).
ViewTensors load_view(const std::filesystem::path& folder, const ModelConfig& config,
                      view::RadianceUnits radiance = view::RadianceUnits::kAbsolute, bool with_probes = true);

// The one batching of views (training, validation, the torch::data loader): each tensor stacked;
// probes and probe_mask stay undefined unless every view has them. Throws on no views.
Batch collate(const std::vector<ViewTensors>& views);

// A mask file (mask_*.exr, first channel) as [1, height, width] of 0/1: 1 where every source
// pixel covered is 1 (as load_view's geometry mask). Undefined when the file does not exist.
torch::Tensor read_mask(const std::filesystem::path& path, int height, int width);

// Image <-> tensor [C, H, W].
torch::Tensor image_to_tensor(const phyir::Image& image);
phyir::Image tensor_to_image(const torch::Tensor& chw);
void write_tensor_image(const std::filesystem::path& path, const torch::Tensor& chw,
                        const std::vector<std::string>& channel_names = {});

// Resizes [N,C,H,W] by area averaging (down) or bilinear interpolation (up).
torch::Tensor resize(const torch::Tensor& x, int height, int width);

// Resamples a probe mosaic ([3, H*hp, W*wp] laid out as `layout`, view/probe_layout.h) to
// probes on an Hr x Wr grid of h x w texels: each probe is area-resized, the grid is sampled
// at the nearest probe (as view::ProbeMosaic::resampled). Returns [Hr, Wr, h, w, 3].
torch::Tensor resample_probes(const torch::Tensor& mosaic, const view::ProbeLayout& layout, int Hr, int Wr, int h, int w);

// A probe mosaic's standard error ([C, H*hp, W*wp], first channel) resampled as resample_probes
// resamples the probes, propagating variances through the same linear resize (an area mean of
// n texels: sqrt(sum sigma_i^2) / n). Returns [Hr, Wr, h, w, 1].
torch::Tensor resample_probe_stderr(const torch::Tensor& mosaic, const view::ProbeLayout& layout, int Hr, int Wr,
                                    int h, int w);

// Probes [Hg, Wg, ...] on an Hr x Wr grid: each target pixel takes the probe of the grid cell
// containing its centre.
torch::Tensor nearest_grid(const torch::Tensor& probes, int Hr, int Wr);

}  // namespace phyir::model
