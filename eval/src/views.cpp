#include "phyir/eval/views.h"

#include <cmath>

#include "phyir/core/colour.h"
#include "phyir/core/error.h"
#include "phyir/core/image_io.h"
#include "phyir/eval/resample.h"

namespace fs = std::filesystem;

namespace phyir::eval {
namespace {

Image read_checked(const fs::path& path, int channels, const std::string& role) {
  if (!fs::is_regular_file(path)) fail("{}: missing ({})", path.string(), role);
  Image image = take_channels(read_image(path), channels, path.string());
  for (float v : image.pixels)
    if (!std::isfinite(v)) fail("{}: holds a non-finite value ({})", path.string(), role);
  return image;
}

void check_size(const Image& image, const Image& reference, const fs::path& path, const fs::path& reference_path) {
  if (image.width != reference.width || image.height != reference.height)
    fail("{}: {}x{} does not match {} ({}x{})", path.string(), image.width, image.height, reference_path.string(),
         reference.width, reference.height);
}

}  // namespace

const std::vector<std::string>& required_prediction_files() {
  static const std::vector<std::string> files = {"depth.exr", "normal.exr", "basecolor.exr", "roughness.exr",
                                                 "metalness.exr"};
  return files;
}

GroundTruthView load_ground_truth(const fs::path& root, const nlohmann::json& record) {
  GroundTruthView v;
  v.id = record.at("id").get<std::string>();
  v.scene = record.at("scene").at("name").get<std::string>();
  v.dir = root / record.at("dir").get<std::string>();
  if (record.contains("input") && record["input"].contains("exposure_stops"))
    v.exposure_stops = record["input"]["exposure_stops"].get<float>();
  if (!fs::is_directory(v.dir)) fail("{}: view folder of {} missing", v.dir.string(), v.id);
  v.color = read_checked(v.dir / "color.exr", 3, "ground-truth colour");
  v.input = read_checked(v.dir / "input.png", 3, "the network's input");
  v.depth = read_checked(v.dir / "depth.exr", 1, "ground-truth depth");
  v.normal = read_checked(v.dir / "normal.exr", 3, "ground-truth normal");
  v.basecolor = read_checked(v.dir / "basecolor.exr", 3, "ground-truth base colour");
  v.roughness = read_checked(v.dir / "roughness.exr", 1, "ground-truth roughness");
  v.metalness = read_checked(v.dir / "metalness.exr", 1, "ground-truth metalness");
  for (const auto& [image, name] : {std::pair{&v.depth, "depth.exr"}, {&v.normal, "normal.exr"},
                                    {&v.basecolor, "basecolor.exr"}, {&v.roughness, "roughness.exr"},
                                    {&v.metalness, "metalness.exr"}, {&v.input, "input.png"}})
    check_size(*image, v.color, v.dir / name, v.dir / "color.exr");
  // Valid pixels: a surface, not a light, not glass (the paper's mask; docs/eval.md).
  v.valid = Image(v.color.width, v.color.height, 1, 1.0f);
  const auto apply = [&](const char* name, bool keep_where_set) {
    const fs::path p = v.dir / name;
    const Image m = read_checked(p, 1, "mask");
    check_size(m, v.color, p, v.dir / "color.exr");
    for (size_t i = 0; i < m.pixels.size(); ++i)
      if ((m.pixels[i] > 0.5f) != keep_where_set) v.valid.pixels[i] = 0.0f;
  };
  apply("mask_geometry.exr", true);
  apply("mask_emissive.exr", false);
  apply("mask_transparent.exr", false);
  const bool has_probes = fs::is_regular_file(v.dir / "probes.exr"), has_mask = fs::is_regular_file(v.dir / "probe_mask.exr");
  if (has_probes != has_mask)
    fail("{}: has {} but not {}", v.dir.string(), has_probes ? "probes.exr" : "probe_mask.exr",
         has_probes ? "probe_mask.exr" : "probes.exr");
  if (has_probes) v.probes = read_probe_set(v.dir / "probes.exr", v.dir / "probe_mask.exr");
  return v;
}

Prediction load_prediction(const fs::path& dir) {
  if (!fs::is_directory(dir)) fail("{}: prediction folder missing (expected {})", dir.string(), "PRED/<view id>/");
  for (const std::string& f : required_prediction_files())
    if (!fs::is_regular_file(dir / f)) fail("{}: missing (a prediction needs {})", (dir / f).string(),
                                             "depth.exr, normal.exr, basecolor.exr, roughness.exr, metalness.exr");
  Prediction p;
  p.depth = read_checked(dir / "depth.exr", 1, "predicted depth");
  p.normal = read_checked(dir / "normal.exr", 3, "predicted normal");
  p.basecolor = read_checked(dir / "basecolor.exr", 3, "predicted base colour");
  p.roughness = read_checked(dir / "roughness.exr", 1, "predicted roughness");
  p.metalness = read_checked(dir / "metalness.exr", 1, "predicted metalness");
  for (const auto& [image, name] : {std::pair{&*p.normal, "normal.exr"}, {&*p.basecolor, "basecolor.exr"},
                                    {&*p.roughness, "roughness.exr"}, {&*p.metalness, "metalness.exr"}})
    check_size(*image, *p.depth, dir / name, dir / "depth.exr");
  if (fs::is_regular_file(dir / "rerender.exr")) p.rerender = read_checked(dir / "rerender.exr", 3, "re-rendered image");
  else p.missing.push_back("rerender.exr");
  const bool has_probes = fs::is_regular_file(dir / "probes.exr"), has_mask = fs::is_regular_file(dir / "probe_mask.exr");
  if (has_probes != has_mask)
    fail("{}: has {} but not {}", dir.string(), has_probes ? "probes.exr" : "probe_mask.exr",
         has_probes ? "probe_mask.exr" : "probes.exr");
  if (has_probes) p.probes = read_probe_set(dir / "probes.exr", dir / "probe_mask.exr");
  else p.missing.push_back("probes.exr");
  return p;
}

}  // namespace phyir::eval
