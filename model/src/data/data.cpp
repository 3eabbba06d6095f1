// Loading view folders into tensors at the network's resolutions.
#include "data.h"

#include <algorithm>
#include <atomic>

#include "nets.h"
#include "phyir/core/colour.h"
#include "phyir/core/error.h"
#include "phyir/core/image_io.h"
#include "phyir/core/log.h"
#include "phyir/view/probe_mosaic.h"
#include "phyir/view/view_files.h"

namespace F = torch::nn::functional;
namespace fs = std::filesystem;

namespace phyir::model {

namespace {

// [C,H,W] from a file, or an undefined tensor when the file is absent and optional.
torch::Tensor read_chw(const fs::path& path, bool required) {
  if (!fs::is_regular_file(path)) {
    if (required) fail("{}: missing (a view folder needs color.exr, depth.exr, normal.exr, basecolor.exr, "
                       "roughness.exr, metalness.exr)", path.string());
    return {};
  }
  return image_to_tensor(read_image(path));
}

torch::Tensor channels(const torch::Tensor& x, int c, const fs::path& what) {
  if (x.size(0) == c) return x;
  if (x.size(0) > c) return x.narrow(0, 0, c);
  if (x.size(0) == 1) return x.expand({c, x.size(1), x.size(2)}).contiguous();
  fail("{}: has {} channels, expected {}", what.string(), x.size(0), c);
}

torch::Tensor to_size(const torch::Tensor& chw, int h, int w) {
  return resize(chw.unsqueeze(0), h, w).squeeze(0);
}

// A mask resized by area stays 1 only where every covered pixel was 1.
torch::Tensor mask_to_size(const torch::Tensor& chw, int h, int w) {
  return (to_size(chw.narrow(0, 0, 1), h, w) > 0.999).to(torch::kFloat);
}

}  // namespace

torch::Tensor read_mask(const fs::path& path, int height, int width) {
  const torch::Tensor m = read_chw(path, false);
  return m.defined() ? mask_to_size(m, height, width) : m;
}

torch::Tensor image_to_tensor(const phyir::Image& image) {
  // Decoded images live in host memory: the tensor starts on the CPU (Batch::to moves it).
  torch::Tensor t = torch::from_blob(const_cast<float*>(image.pixels.data()),
                                     {image.height, image.width, image.channels},
                                     torch::TensorOptions().dtype(torch::kFloat).device(torch::kCPU));
  return t.permute({2, 0, 1}).clone();
}

phyir::Image tensor_to_image(const torch::Tensor& chw_in) {
  const torch::Tensor chw = chw_in.detach().to(torch::kCPU, torch::kFloat).contiguous();
  const int C = static_cast<int>(chw.size(0)), H = static_cast<int>(chw.size(1)), W = static_cast<int>(chw.size(2));
  phyir::Image image(W, H, C);
  const torch::Tensor hwc = chw.permute({1, 2, 0}).contiguous();
  std::copy(hwc.data_ptr<float>(), hwc.data_ptr<float>() + hwc.numel(), image.pixels.begin());
  return image;
}

void write_tensor_image(const fs::path& path, const torch::Tensor& chw, const std::vector<std::string>& channel_names) {
  write_image(path, tensor_to_image(chw), channel_names);
}

torch::Tensor resize(const torch::Tensor& x, int height, int width) {
  if (x.size(2) == height && x.size(3) == width) return x;
  if (x.size(2) >= height && x.size(3) >= width)
    return F::adaptive_avg_pool2d(x, F::AdaptiveAvgPool2dFuncOptions({height, width}));
  return F::interpolate(x, F::InterpolateFuncOptions()
                               .size(std::vector<int64_t>{height, width})
                               .mode(torch::kBilinear)
                               .align_corners(false));
}

torch::Tensor resample_probes(const torch::Tensor& mosaic, const view::ProbeLayout& layout, int Hr, int Wr, int h,
                              int w) {
  const int grid_h = layout.grid_height, grid_w = layout.grid_width, hp = layout.res_height, wp = layout.res_width;
  torch::Tensor probes = mosaic_to_probes(mosaic.unsqueeze(0), hp, wp).squeeze(0);  // [Hg,Wg,hp,wp,3]
  if (hp != h || wp != w) {
    torch::Tensor imgs = probes.reshape({grid_h * grid_w, hp, wp, 3}).permute({0, 3, 1, 2});
    imgs = resize(imgs, h, w);
    probes = imgs.permute({0, 2, 3, 1}).reshape({grid_h, grid_w, h, w, 3});
  }
  probes = nearest_grid(probes, Hr, Wr);
  return probes.contiguous();
}

namespace {

// The network's input: input.png, or (a `phyir render` folder) color.exr through the
// dataset's display transform at the view's exposure.
torch::Tensor load_input(const fs::path& dir, const torch::Tensor& color, const view::InputExposure& exposure, int h,
                         int w) {
  torch::Tensor input = read_chw(dir / view::kInputFile, false);
  if (!input.defined()) {
    if (!color.defined()) fail("{}: neither input.png nor color.exr", dir.string());
    input = image_to_tensor(linear_to_display(read_image(dir / view::kColorFile), static_cast<float>(exposure.stops),
                                              exposure.raw_view() ? "Raw" : "Standard"));
  } else if (!exposure.recorded) {
    static std::atomic<bool> warned{false};
    if (!warned.exchange(true))
      spdlog::warn("{}: input.png without a view.json exposure: taken as written at 0 stops (docs/model.md)",
                   dir.string());
  }
  return to_size(channels(input, 3, dir / view::kInputFile), h, w).clamp(0.0, 1.0);
}

// Surface, not emissive, not transparent, at the rendering resolution. `emissive` and
// `transparent`: the mask files as read (undefined when absent).
torch::Tensor load_render_mask(const torch::Tensor& geometry, const torch::Tensor& emissive,
                               const torch::Tensor& transparent, int Hr, int Wr) {
  torch::Tensor render_mask = mask_to_size(geometry, Hr, Wr);
  for (const torch::Tensor* m : {&emissive, &transparent}) {
    if (!m->defined()) continue;
    torch::Tensor excluded = (to_size(m->narrow(0, 0, 1), Hr, Wr) > 0.0).to(torch::kFloat);
    // color.exr is box-filtered over each pixel, the AOVs come from the pixel centre: a pixel
    // next to a light can hold part of the light's radiance while its AOVs describe the
    // surface beside it. Leave those out too (3x3 dilation, wrapping in u).
    if (m == &emissive)
      excluded = F::max_pool2d(cirpad(excluded.unsqueeze(0), 1, 1), F::MaxPool2dFuncOptions(3).stride(1)).squeeze(0);
    render_mask = render_mask * (1.0 - excluded);
  }
  return render_mask;
}

// A mask file at the input resolution, zeros when the view has none.
torch::Tensor mask_or_zeros(const torch::Tensor& m, int h, int w) {
  return m.defined() ? mask_to_size(m, h, w) : torch::zeros({1, h, w});
}

// probes.exr on the rendering grid and its validity (probe_mask.exr and the render mask).
void load_probes(const fs::path& dir, const ModelConfig& c, ViewTensors& v) {
  if (!view::has_probes(dir)) return;
  const view::ProbeMosaic probes = view::read_probe_mosaic(dir);
  const int Hr = c.render_height, Wr = c.render_width;
  v.probes = resample_probes(image_to_tensor(probes.radiance), probes.layout, Hr, Wr, c.probe_height, c.probe_width);
  const torch::Tensor pmask = image_to_tensor(probes.mask);
  const view::ProbeLayout mask_layout{probes.layout.grid_height, probes.layout.grid_width, 1, 1};
  v.probe_mask = (resample_probes(channels(pmask.narrow(0, 0, 1), 3, dir / view::kProbeMaskFile), mask_layout, Hr, Wr,
                                  1, 1)
                      .select(4, 0)
                      .reshape({1, Hr, Wr}) > 0.5)
                     .to(torch::kFloat) *
                 v.render_mask;
  if (probes.standard_error.pixels.empty()) return;
  v.probe_stderr = resample_probe_stderr(image_to_tensor(probes.standard_error), probes.layout, Hr, Wr,
                                         c.probe_height, c.probe_width);
  if (!torch::isfinite(v.probe_stderr).all().item<bool>())
    fail("{}: non-finite values", (dir / view::kProbeStderrFile).string());
}

}  // namespace

ViewTensors load_view(const fs::path& folder, const ModelConfig& c, view::RadianceUnits radiance, bool with_probes) {
  return load_view(view::read_view(folder), c, radiance, with_probes);
}

ViewTensors load_view(const view::ViewRecord& record, const ModelConfig& c, view::RadianceUnits radiance,
                      bool with_probes) {
  const fs::path& dir = record.dir;
  ViewTensors v;
  v.name = dir.filename().string();
  v.exposure = record.input;
  const int Hi = c.input_height, Wi = c.input_width, Hr = c.render_height, Wr = c.render_width;
  const torch::Tensor color = read_chw(dir / view::kColorFile, false);
  v.image = load_input(dir, color, v.exposure, Hi, Wi);
  if (!color.defined()) fail("{}: missing color.exr (the re-render target)", (dir / view::kColorFile).string());
  v.color_lo = to_size(channels(color, 3, dir / view::kColorFile), Hr, Wr);
  v.depth = to_size(channels(read_chw(dir / view::kDepthFile, true), 1, dir / view::kDepthFile), Hi, Wi);
  v.normal = F::normalize(to_size(channels(read_chw(dir / view::kNormalFile, true), 3, dir / view::kNormalFile), Hi, Wi),
                          F::NormalizeFuncOptions().dim(0).eps(1e-6));
  v.base_color = to_size(channels(read_chw(dir / view::kBaseColorFile, true), 3, dir / view::kBaseColorFile), Hi, Wi);
  v.roughness = to_size(channels(read_chw(dir / view::kRoughnessFile, true), 1, dir / view::kRoughnessFile), Hi, Wi);
  v.metalness = to_size(channels(read_chw(dir / view::kMetalnessFile, true), 1, dir / view::kMetalnessFile), Hi, Wi);
  torch::Tensor geometry = read_chw(dir / view::kMaskGeometryFile, false);
  if (!geometry.defined()) geometry = (read_chw(dir / view::kDepthFile, true).narrow(0, 0, 1) > 0).to(torch::kFloat);
  v.mask = mask_to_size(geometry, Hi, Wi);
  const torch::Tensor emissive = read_chw(dir / view::kMaskEmissiveFile, false);
  const torch::Tensor transparent = read_chw(dir / view::kMaskTransparentFile, false);
  v.mask_emissive = mask_or_zeros(emissive, Hi, Wi);
  v.mask_transparent = mask_or_zeros(transparent, Hi, Wi);
  v.render_mask = load_render_mask(geometry, emissive, transparent, Hr, Wr);
  if (with_probes) load_probes(dir, c, v);
  for (const torch::Tensor* t : {&v.image, &v.depth, &v.normal, &v.base_color, &v.roughness, &v.metalness, &v.color_lo})
    if (!torch::isfinite(*t).all().item<bool>()) fail("{}: non-finite values in the maps", dir.string());
  if (radiance == view::RadianceUnits::kInput) {
    const double f = v.exposure.factor();
    v.color_lo = v.color_lo * f;
    if (v.probes.defined()) v.probes = v.probes * f;
    // A standard error scales with the radiance it is the error of.
    if (v.probe_stderr.defined()) v.probe_stderr = v.probe_stderr * f;
  }
  return v;
}

Batch collate(const std::vector<ViewTensors>& views) {
  if (views.empty()) fail("collate: no views");
  auto stack = [&](torch::Tensor ViewTensors::*member) {
    std::vector<torch::Tensor> parts;
    for (const ViewTensors& v : views) {
      if (!(v.*member).defined()) return torch::Tensor();
      parts.push_back(v.*member);
    }
    return torch::stack(parts, 0);
  };
  Batch b;
  std::vector<int64_t> index;
  for (const ViewTensors& v : views) {
    b.ids.push_back(v.id.empty() ? v.name : v.id);
    index.push_back(v.index);
    if (v.census) b.census.push_back(v.census);
    if (v.probes.defined() && !v.probe_stderr.defined()) b.without_probe_stderr.push_back(b.ids.back());
  }
  b.index = torch::tensor(index, torch::TensorOptions().dtype(torch::kLong));
  b.image = stack(&ViewTensors::image);
  b.depth = stack(&ViewTensors::depth);
  b.normal = stack(&ViewTensors::normal);
  b.base_color = stack(&ViewTensors::base_color);
  b.roughness = stack(&ViewTensors::roughness);
  b.metalness = stack(&ViewTensors::metalness);
  b.mask = stack(&ViewTensors::mask);
  b.mask_emissive = stack(&ViewTensors::mask_emissive);
  b.mask_transparent = stack(&ViewTensors::mask_transparent);
  b.color_lo = stack(&ViewTensors::color_lo);
  b.render_mask = stack(&ViewTensors::render_mask);
  b.probes = stack(&ViewTensors::probes);
  b.probe_mask = stack(&ViewTensors::probe_mask);
  b.probe_stderr = stack(&ViewTensors::probe_stderr);
  return b;
}

Batch Batch::to(const torch::Device& device) const {
  if (device.is_cpu()) return *this;
  const auto move = [&](const torch::Tensor& t) { return t.defined() ? t.to(device) : t; };
  Batch b = *this;
  for (torch::Tensor Batch::*m : {&Batch::index, &Batch::image, &Batch::depth, &Batch::normal, &Batch::base_color,
                                  &Batch::roughness, &Batch::metalness, &Batch::mask, &Batch::mask_emissive,
                                  &Batch::mask_transparent, &Batch::color_lo, &Batch::render_mask, &Batch::probes,
                                  &Batch::probe_mask, &Batch::probe_stderr})
    b.*m = move(this->*m);
  return b;
}

}  // namespace phyir::model
