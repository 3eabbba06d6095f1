// export-futurehouse: one of our datasets in FutureHouse's layout (futurehouse_layout.h).
#include <tbb/global_control.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>

#include <map>
#include <mutex>

#include <fmt/format.h>

#include "futurehouse_folder.h"
#include "phyir/core/atomic_file.h"
#include "phyir/core/error.h"
#include "phyir/core/image_io.h"
#include "phyir/core/progress.h"
#include "phyir/dataset/futurehouse.h"
#include "phyir/dataset/futurehouse_layout.h"
#include "phyir/dataset/manifest.h"
#include "phyir/view/view_files.h"

namespace phyir::dataset {

namespace fs = std::filesystem;
namespace fh = futurehouse;
using nlohmann::json;

namespace {

struct ExportView {
  std::string plan;  // our scene
  int index = 0;     // FutureHouse's view index: its position among the scene's views here
  std::string id;    // ours
  fs::path dir;      // ours, absolute
  bool light = false;
};

// R = G = B = value(x, y): the loader reads one channel of a single-value map.
Image grey(const Image& single, float (*encode)(float)) {
  Image out(single.width, single.height, 3);
  for (int y = 0; y < single.height; ++y)
    for (int x = 0; x < single.width; ++x) {
      const float v = encode ? encode(single.at(x, y, 0)) : single.at(x, y, 0);
      for (int c = 0; c < 3; ++c) out.at(x, y, c) = v;
    }
  return out;
}

Image rgb(const Image& image) {
  if (image.channels == 3) return image;
  Image out(image.width, image.height, 3);
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x)
      for (int c = 0; c < 3; ++c) out.at(x, y, c) = image.at(x, y, std::min(c, image.channels - 1));
  return out;
}

// (n + 1) / 2 in FutureHouse's axes; pixels without a surface (n = 0) become 0.5 grey.
Image encode_normals(const Image& normal, const fh::NormalAxes& axes) {
  Image out(normal.width, normal.height, 3);
  for (int y = 0; y < normal.height; ++y)
    for (int x = 0; x < normal.width; ++x) {
      const glm::vec3 theirs =
          axes.to_theirs({normal.at(x, y, 0), normal.at(x, y, 1), normal.at(x, y, 2)});
      for (int c = 0; c < 3; ++c) out.at(x, y, c) = fh::encode_normal(theirs[c]);
    }
  return out;
}

// The paper's M_mask: a surface, not emissive, not transparent.
Image render_mask(const fs::path& dir) {
  const Image geometry = read_image(dir / view::kMaskGeometryFile);
  const Image emissive = read_image(dir / view::kMaskEmissiveFile);
  const Image transparent = read_image(dir / view::kMaskTransparentFile);
  Image mask(geometry.width, geometry.height, 1);
  for (size_t i = 0; i < mask.pixels.size(); ++i)
    mask.pixels[i] = geometry.pixels[i * size_t(geometry.channels)] > 0.5f &&
                             emissive.pixels[i * size_t(emissive.channels)] <= 0.5f &&
                             transparent.pixels[i * size_t(transparent.channels)] <= 0.5f
                         ? 1.0f
                         : 0.0f;
  return mask;
}

void export_view(const fs::path& out, const ExportView& v, const fh::NormalAxes& axes) {
  const auto map = [&](fh::Map m) { return fh::map_path(out, v.plan, v.index, m); };
  write_image(map(fh::Map::Image), rgb(read_image(v.dir / view::kColorFile)));
  write_image(map(fh::Map::Albedo), rgb(read_image(v.dir / view::kBaseColorFile)));
  write_image(map(fh::Map::Roughness), grey(read_image(v.dir / view::kRoughnessFile), nullptr));
  write_image(map(fh::Map::Metallic), grey(read_image(v.dir / view::kMetalnessFile), nullptr));
  write_image(map(fh::Map::Mask), grey(render_mask(v.dir), nullptr));
  write_image(map(fh::Map::Normal), encode_normals(read_image(v.dir / view::kNormalFile), axes));
  write_image(map(fh::Map::Depth), grey(read_image(v.dir / view::kDepthFile), fh::encode_depth));
  // What FutureHouse has no slot for, outside the loader's paths.
  for (const char* name : {"mask_emissive", "mask_transparent"})
    write_image(fh::sidecar_path(out, v.plan, v.index, name), read_image(v.dir / (std::string(name) + ".exr")));
  if (!v.light) return;
  write_image(fh::light_path(out, v.plan, v.index), rgb(read_image(v.dir / view::kProbesFile)));
  write_image(fh::sidecar_path(out, v.plan, v.index, "probe_mask"), read_image(v.dir / view::kProbeMaskFile));
}

std::vector<ExportView> plan_export(const fs::path& dataset, const Manifest& m, ExportProbes probes) {
  const bool has_probes = m.settings.contains("probes") && m.settings["probes"].is_object();
  std::map<std::string, int> count;
  std::vector<ExportView> views;
  for (const json& record : m.views) {
    ExportView v;
    v.plan = record.at("scene").at("name").get<std::string>();
    v.index = count[v.plan]++;
    v.id = record.at("id").get<std::string>();
    v.dir = dataset / record.at("dir").get<std::string>();
    v.light = has_probes && (probes == ExportProbes::kAll || (probes == ExportProbes::kFirst && v.index == 0));
    views.push_back(std::move(v));
  }
  return views;
}

json split_json(const Manifest& m) {
  json split = {{"train", json::array()}, {"val", json::array()}, {"test", json::array()}};
  for (const json& s : m.scenes) split[s.at("split").get<std::string>()].push_back(s.at("name"));
  return split;
}

// ROOT/phyir/export.json: where each view came from and how it was written, so an import
// restores our data exactly (up to the files' precision).
json export_record(const fs::path& dataset, const Manifest& m, const std::vector<ExportView>& views,
                   const FutureHouseExportOptions& o) {
  json list = json::array();
  for (const ExportView& v : views) list.push_back({{"plan", v.plan}, {"index", v.index}, {"id", v.id}, {"light", v.light}});
  json probes = nullptr;
  if (m.settings.contains("probes") && m.settings["probes"].is_object())
    probes = {{"grid", m.settings["probes"]["grid"]}, {"resolution", m.settings["probes"]["resolution"]}};
  return {{"format", fh::kExportFormat},
          {"format_version", 1},
          {"generator", std::string("phyir ") + PHYIR_VERSION},
          {"dataset", dataset.generic_string()},
          {"normal_axes", fh::NormalAxes::parse(o.normal_axes).name()},
          {"probes", probes},
          {"sidecar", "phyir/<plan>/<i>_mask_emissive.exr, <i>_mask_transparent.exr, <i>_probe_mask.exr: our masks, "
                      "which FutureHouse's files cannot hold"},
          {"views", list}};
}

}  // namespace

FutureHouseExportSummary export_futurehouse(const FutureHouseExportOptions& o) {
  const Manifest m = read_manifest(o.dataset);
  const fh::NormalAxes axes = fh::NormalAxes::parse(o.normal_axes);
  const std::vector<ExportView> views = plan_export(o.dataset, m, o.probes);
  PartialFolder folder(o.out);
  const int n = o.threads > 0 ? o.threads : tbb::info::default_concurrency();
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, n);
  Progress progress("export-futurehouse", views.size(), "views", o.progress);
  std::mutex mutex;
  std::string first_error;
  tbb::parallel_for(size_t(0), views.size(), [&](size_t i) {
    try {
      export_view(folder.path(), views[i], axes);
    } catch (const std::exception& e) {
      std::lock_guard<std::mutex> lock(mutex);
      if (first_error.empty()) first_error = fmt::format("{}: {}", views[i].id, e.what());
    }
    progress.advance();
  });
  progress.finish();
  if (!first_error.empty()) fail("export-futurehouse {}: {}", o.out.string(), first_error);
  write_file_atomic(folder.path() / fh::kSplitFile, split_json(m).dump(2) + "\n");
  write_file_atomic(folder.path() / fh::kSidecarFolder / fh::kExportRecordFile,
                    export_record(o.dataset, m, views, o).dump(2) + "\n");
  folder.commit();
  FutureHouseExportSummary summary;
  summary.plans = m.scenes.size();
  summary.views = views.size();
  for (const ExportView& v : views) summary.light_files += v.light ? 1 : 0;
  return summary;
}

}  // namespace phyir::dataset
