// phyir infer: the model on one panorama, outputs in the renderer's conventions, radiance in
// absolute units when the input's exposure is known (docs/commands/infer.md).
#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "host_memory.h"
#include "checkpoint.h"
#include "data.h"
#include "device.h"
#include "exposure.h"
#include "phyir/core/atomic_file.h"
#include "phyir/core/colour.h"
#include "phyir/core/error.h"
#include "phyir/core/image_io.h"
#include "phyir/core/log.h"
#include "phyir/dataset/input_image.h"
#include "phyir/model/training.h"
#include "phyir/view/input_exposure.h"
#include "phyir/view/probe_mosaic.h"
#include "phyir/view/view_files.h"
#include "phyir/view/view_record.h"
#include "predict.h"

namespace fs = std::filesystem;
using nlohmann::json;

namespace phyir::model {

namespace {

// The panorama as the network sees it (sRGB-encoded, [0,1]) and the exposure it was made at.
struct Panorama {
  torch::Tensor image;          // [1,3,H,W]
  double exposure_stops = NAN;  // NaN: unknown
  std::string exposure_source;  // where the exposure came from
};

Panorama read_panorama(const InferOptions& o) {
  const fs::path in(o.input);
  if (!fs::is_regular_file(in)) fail("{}: input panorama not found", o.input);
  std::string ext = in.extension().string();
  for (auto& ch : ext) ch = static_cast<char>(std::tolower(ch));
  Panorama p;
  phyir::Image img = read_image(in);
  if (ext == ".exr" || ext == ".hdr") {
    // HDR: exposed as the dataset exposes its views (auto: the 95th percentile to 0.9),
    // unless the options give an exposure, then the sRGB display's Standard view.
    p.exposure_stops = std::isfinite(o.exposure) ? o.exposure
                                                 : dataset::choose_input_exposure(img, dataset::InputSettings{}, 0).stops;
    p.exposure_source = std::isfinite(o.exposure) ? "given" : "auto (95th percentile to 0.9, as phyir dataset)";
    img = linear_to_display(img, static_cast<float>(p.exposure_stops), "Standard");
  } else if (std::isfinite(o.exposure)) {
    p.exposure_stops = o.exposure;
    p.exposure_source = "given";
  } else if (const view::InputExposure e = view::read_view(in.parent_path()).input; e.recorded) {
    p.exposure_stops = e.stops;  // input.png of a dataset view folder
    p.exposure_source = (in.parent_path() / view::kViewRecordFile).string();
  }
  torch::Tensor x = image_to_tensor(img);
  if (x.size(0) == 1) x = x.expand({3, x.size(1), x.size(2)});
  p.image = x.narrow(0, 0, 3).unsqueeze(0).contiguous().clamp(0.0, 1.0);
  if (p.image.size(3) != 2 * p.image.size(2))
    spdlog::warn("{}: {}x{} is not a 2:1 equirect panorama", o.input, p.image.size(3), p.image.size(2));
  return p;
}

json radiance_record(const Panorama& p, bool absolute, bool trained_absolute) {
  if (trained_absolute)
    return {{"unit", "absolute"}, {view::kExposureStopsKey, std::isfinite(p.exposure_stops) ? json(p.exposure_stops) : json()},
            {"meaning", "radiance as color.exr and probes.exr hold it: the network's output (trained with "
                        "absolute target units)"}};
  if (absolute)
    return {{"unit", "absolute"}, {view::kExposureStopsKey, p.exposure_stops}, {"exposure_source", p.exposure_source},
            {"meaning", "radiance as color.exr and probes.exr hold it: the network's output / 2^exposure_stops"}};
  json j = {{"unit", "input"},
            {"meaning", "the input's relative units: radiance x 2^exposure_stops of the input, the scale in which "
                        "the input's linear (sRGB-decoded) values are radiance"}};
  j[view::kExposureStopsKey] = std::isfinite(p.exposure_stops) ? json(p.exposure_stops) : json();
  if (std::isfinite(p.exposure_stops)) j["exposure_source"] = p.exposure_source;
  return j;
}

}  // namespace

void infer(const InferOptions& o) {
  init_logging();
  set_threads(o.threads);
  retain_freed_memory();
  torch::manual_seed(o.seed);
  const torch::Device device = parse_device(o.device);
  const ModelConfig cfg = read_checkpoint_config(o.checkpoint);
  Networks nets(cfg);
  const json meta = load_checkpoint(o.checkpoint, &nets, nullptr, false, device);
  nets.to(device);
  nets.gmnet->eval();
  nets.lnet->eval();
  nets.gsnet->eval();
  torch::NoGradGuard no_grad;

  const Panorama pano = read_panorama(o);
  const int Hp = static_cast<int>(pano.image.size(2)), Wp = static_cast<int>(pano.image.size(3));
  const torch::Tensor x = resize(pano.image.to(device), cfg.input_height, cfg.input_width).clamp(0.0, 1.0);
  const bool use_gs = meta.at("trained").value("gsnet", false);
  const ModelOutput p = predict(nets, cfg, x, use_gs, true);
  // A model trained on absolute targets (target units "absolute") predicts absolute radiance.
  const bool trained_absolute = target_radiance(cfg) == view::RadianceUnits::kAbsolute;
  const bool absolute = trained_absolute || (o.absolute && std::isfinite(pano.exposure_stops));
  if (o.absolute && !absolute)
    spdlog::warn("{}: the input's exposure is unknown (none given, no view.json beside it): probes.exr and "
                 "rerender.exr are in the input's relative units",
                 o.input);
  const double to_output = absolute && !trained_absolute ? std::exp2(-pano.exposure_stops) : 1.0;

  const fs::path out(o.out_dir);
  fs::create_directories(out);
  // Maps at the panorama's resolution (bilinear up, area down), as the renderer writes its AOVs
  // at the colour's resolution; normals renormalised after the interpolation.
  auto full = [&](const torch::Tensor& m) { return resize(m, Hp, Wp); };
  const torch::Tensor normal_full = normalize_channels(full(p.maps.normal));
  write_tensor_image(out / view::kInputFile, pano.image[0]);
  write_tensor_image(out / view::kDepthFile, full(p.maps.depth)[0], {"Y"});
  write_tensor_image(out / view::kNormalFile, normal_full[0], {"X", "Y", "Z"});
  write_tensor_image(out / view::kBaseColorFile, full(p.maps.base_color).clamp(0.0, 1.0)[0], {"R", "G", "B"});
  write_tensor_image(out / view::kRoughnessFile, full(p.maps.roughness).clamp(0.0, 1.0)[0], {"Y"});
  write_tensor_image(out / view::kMetalnessFile, full(p.maps.metalness).clamp(0.0, 1.0)[0], {"Y"});
  view::ProbeMosaic probes;
  probes.layout = {cfg.render_height, cfg.render_width, cfg.probe_height, cfg.probe_width};
  probes.radiance = tensor_to_image(probes_to_mosaic(p.probes * to_output)[0]);
  probes.mask = phyir::Image(cfg.render_width, cfg.render_height, 1, 1.0f);  // every predicted probe is valid
  view::write_probe_mosaic(out, probes);
  write_tensor_image(out / view::kRerenderFile, (p.rerender * to_output)[0], {"R", "G", "B"});
  json info = {{"checkpoint", o.checkpoint}, {"input", o.input}, {"device", device.str()},
               {"config", config_to_json(cfg)},
               {"maps_resolution", {Wp, Hp}}, {"network_input_resolution", {cfg.input_width, cfg.input_height}},
               {"probe_grid", {cfg.render_width, cfg.render_height}},
               {"trained", meta.at("trained")}, {"guided_filter_applied", use_gs},
               {"radiance", radiance_record(pano, absolute, trained_absolute)},
               {"conventions", {{"equirect", "row 0 = +Y, centre column = -Z, u = 0.5 + atan2(x,-z)/2pi, v = acos(y)/pi"},
                                {"depth", "Euclidean distance, metres"}, {"normal", "world space, unit"},
                                {"probes", "mosaic: probe (i,j) is the h x w world-oriented equirect block at row i*h, col j*w"}}},
               {"timings_ms", {{"gmnet", p.gmnet_ms}, {"gsnet", p.gsnet_ms}, {"lnet_and_render", p.light_ms}}}};
  write_file_atomic(out / view::kInferRecordFile, info.dump(2) + "\n");
  for (const char* m : {"gmnet", "lnet", "gsnet"})
    if (!meta.at("trained").value(m, false)) spdlog::warn("{}: {} was never trained (random weights)", o.checkpoint, m);
  spdlog::info("infer: wrote {}; probes and re-render in {} (GMNet {:.0f} ms, GSNet {:.0f} ms, LNet + rendering "
               "{:.0f} ms)",
               out.string(),
               trained_absolute ? std::string("absolute radiance (the model was trained on absolute targets)")
               : absolute ? fmt::format("absolute radiance (exposure {:+.3f} stops, {})", pano.exposure_stops,
                                      pano.exposure_source)
                        : std::string("the input's relative units"),
               p.gmnet_ms, p.gsnet_ms, p.light_ms);
}

}  // namespace phyir::model
