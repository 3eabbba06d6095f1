#include "phyir/eval/views.h"

#include <cmath>

#include <fmt/ranges.h>

#include "phyir/core/colour.h"
#include "phyir/core/error.h"
#include "phyir/core/image_io.h"
#include "phyir/core/image_resample.h"
#include "phyir/view/view_files.h"

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

GroundTruthView load_ground_truth(const view::ViewRecord& record) {
  using namespace view;
  GroundTruthView v;
  v.id = record.id;
  v.scene = record.scene;
  v.dir = record.dir;
  v.exposure_stops = float(record.input.stops);
  if (!fs::is_directory(v.dir)) fail("{}: view folder of {} missing", v.dir.string(), v.id);
  v.color = read_checked(v.dir / kColorFile, 3, "ground-truth colour");
  v.input = read_checked(v.dir / kInputFile, 3, "the network's input");
  v.depth = read_checked(v.dir / kDepthFile, 1, "ground-truth depth");
  v.normal = read_checked(v.dir / kNormalFile, 3, "ground-truth normal");
  v.basecolor = read_checked(v.dir / kBaseColorFile, 3, "ground-truth base colour");
  v.roughness = read_checked(v.dir / kRoughnessFile, 1, "ground-truth roughness");
  v.metalness = read_checked(v.dir / kMetalnessFile, 1, "ground-truth metalness");
  for (const auto& [image, name] : {std::pair{&v.depth, kDepthFile}, {&v.normal, kNormalFile},
                                    {&v.basecolor, kBaseColorFile}, {&v.roughness, kRoughnessFile},
                                    {&v.metalness, kMetalnessFile}, {&v.input, kInputFile}})
    check_size(*image, v.color, v.dir / name, v.dir / kColorFile);
  // Valid pixels: a surface, not a light, not glass (the paper's mask; docs/eval.md).
  v.valid = Image(v.color.width, v.color.height, 1, 1.0f);
  const auto apply = [&](const char* name, bool keep_where_set) {
    const fs::path p = v.dir / name;
    const Image m = read_checked(p, 1, "mask");
    check_size(m, v.color, p, v.dir / kColorFile);
    for (size_t i = 0; i < m.pixels.size(); ++i)
      if ((m.pixels[i] > 0.5f) != keep_where_set) v.valid.pixels[i] = 0.0f;
  };
  apply(kMaskGeometryFile, true);
  apply(kMaskEmissiveFile, false);
  apply(kMaskTransparentFile, false);
  if (has_probes(v.dir)) v.probes = read_probe_mosaic(v.dir);
  return v;
}

Prediction load_prediction(const fs::path& dir) {
  using namespace view;
  const std::vector<std::string>& maps = prediction_map_files();
  if (!fs::is_directory(dir)) fail("{}: prediction folder missing (expected {})", dir.string(), "PRED/<view id>/");
  for (const std::string& f : maps)
    if (!fs::is_regular_file(dir / f))
      fail("{}: missing (a prediction needs {})", (dir / f).string(), fmt::format("{}", fmt::join(maps, ", ")));
  Prediction p;
  p.depth = read_checked(dir / kDepthFile, 1, "predicted depth");
  p.normal = read_checked(dir / kNormalFile, 3, "predicted normal");
  p.basecolor = read_checked(dir / kBaseColorFile, 3, "predicted base colour");
  p.roughness = read_checked(dir / kRoughnessFile, 1, "predicted roughness");
  p.metalness = read_checked(dir / kMetalnessFile, 1, "predicted metalness");
  for (const auto& [image, name] : {std::pair{&*p.normal, kNormalFile}, {&*p.basecolor, kBaseColorFile},
                                    {&*p.roughness, kRoughnessFile}, {&*p.metalness, kMetalnessFile}})
    check_size(*image, *p.depth, dir / name, dir / kDepthFile);
  if (fs::is_regular_file(dir / kRerenderFile)) p.rerender = read_checked(dir / kRerenderFile, 3, "re-rendered image");
  else p.missing.push_back(kRerenderFile);
  if (has_probes(dir)) p.probes = read_probe_mosaic(dir);
  else p.missing.push_back(kProbesFile);
  return p;
}

}  // namespace phyir::eval
