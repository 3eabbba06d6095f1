// import-futurehouse: FutureHouse's release layout (futurehouse_layout.h) into one of our
// datasets (docs/dataset.md), manifest included, so verify, train and eval read it.
#include <tbb/global_control.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>

#include <atomic>
#include <cmath>
#include <map>
#include <mutex>
#include <set>

#include <fmt/format.h>

#include "futurehouse_folder.h"
#include "phyir/core/atomic_file.h"
#include "phyir/core/equirect.h"
#include "phyir/core/error.h"
#include "phyir/core/setting_error.h"
#include "phyir/core/image_io.h"
#include "phyir/core/log.h"
#include "phyir/core/progress.h"
#include "phyir/dataset/checksum.h"
#include "phyir/dataset/futurehouse.h"
#include "phyir/dataset/futurehouse_layout.h"
#include "phyir/dataset/input_image.h"
#include "phyir/dataset/layout.h"
#include "phyir/dataset/manifest.h"
#include "phyir/dataset/verify.h"
#include "phyir/view/probe_mosaic.h"
#include "phyir/view/view_files.h"
#include "phyir/view/view_record.h"

namespace phyir::dataset {

namespace fs = std::filesystem;
namespace fh = futurehouse;
using nlohmann::json;

namespace {

// A plan of split.json as found on disk.
struct SourcePlan {
  std::string name, split;
  int views = 0;            // views 0 .. views-1, each with its 7 maps
  std::vector<bool> light;  // per view: has <i>_light.exr
  std::string problem;      // why it cannot be imported ("" = fine)
};

struct ImportView {
  std::string plan, split;
  int source_index = 0;  // FutureHouse's i
  int index = 0;         // ours: v000 ..
  bool light = false;
};

// What every view's conversion needs.
struct ImportContext {
  fs::path src, out;
  fh::NormalAxes axes;
  bool sidecar = false, probes = false;
  int width = 0, height = 0, probe_height = 0, probe_width = 0, grid_height = 0, grid_width = 0;
  int views_per_scene = 0;
  InputSettings input;
  uint64_t seed = 1;
  std::string settings_sha256;
};

// split.json: {"train": [plan, ..], "val": [..], "test": [..]} -> plan -> split.
std::map<std::string, std::string> read_split(const fs::path& file) {
  std::error_code ec;
  if (!fs::is_regular_file(file, ec))
    fail_setting("split_file", "{}: no split file (FutureHouse's split.json; give another)", file.string());
  const json j = json::parse(read_file(file), nullptr, false);
  if (j.is_discarded() || !j.is_object()) fail("{}: not a JSON object", file.string());
  std::map<std::string, std::string> split_of;
  for (auto it = j.begin(); it != j.end(); ++it) {
    if (it.key() != "train" && it.key() != "val" && it.key() != "test")
      fail("{}: split \"{}\" is not train, val or test", file.string(), it.key());
    if (!it.value().is_array()) fail("{}: \"{}\" is not an array of plan ids", file.string(), it.key());
    for (const json& plan : it.value()) {
      if (!plan.is_string() || plan.get<std::string>().empty() || plan.get<std::string>().find('/') != std::string::npos)
        fail("{}: \"{}\" holds {}, not a plan id", file.string(), it.key(), plan.dump());
      const auto [at, fresh] = split_of.emplace(plan.get<std::string>(), it.key());
      if (!fresh) fail("{}: plan {} is in {} and {}", file.string(), at->first, at->second, it.key());
    }
  }
  if (split_of.empty()) fail("{}: lists no plans", file.string());
  return split_of;
}

// Views 0 .. n-1 of a plan, as the loader counts them (files / 7), each checked for its maps.
SourcePlan scan_plan(const fs::path& src, const std::string& name, const std::string& split) {
  SourcePlan plan{name, split, 0, {}, ""};
  const fs::path folder = fh::maps_folder(src, name);
  std::error_code ec;
  if (!fs::is_directory(folder, ec)) {
    plan.problem = fmt::format("no folder {}", fs::relative(folder, src, ec).generic_string());
    return plan;
  }
  size_t files = 0;
  for (const fs::directory_entry& entry : fs::directory_iterator(folder, ec)) files += entry.is_regular_file() ? 1 : 0;
  if (files == 0 || files % fh::kMapsPerView != 0) {
    plan.problem = fmt::format("{} holds {} files, not 7 per view (the published loader skips it too)",
                               folder.string(), files);
    return plan;
  }
  const int n = int(files / fh::kMapsPerView);
  for (int i = 0; i < n; ++i)
    for (fh::Map map : fh::kMaps)
      if (!fs::is_regular_file(fh::map_path(src, name, i, map), ec)) {
        plan.problem = fmt::format("{} is missing", fh::map_path(src, name, i, map).string());
        return plan;
      }
  plan.views = n;
  for (int i = 0; i < n; ++i) plan.light.push_back(fs::is_regular_file(fh::light_path(src, name, i), ec));
  return plan;
}

// The views to import: per plan the first K that qualify (with a light file for kOnly).
std::vector<ImportView> choose_views(const std::vector<SourcePlan>& plans, ImportProbes probes, int wanted_k,
                                     int* k_out, std::vector<std::string>& left_out) {
  std::map<std::string, std::vector<int>> candidates;
  int k = wanted_k;
  for (const SourcePlan& p : plans) {
    if (!p.problem.empty()) continue;
    std::vector<int>& c = candidates[p.name];
    for (int i = 0; i < p.views; ++i)
      if (probes != ImportProbes::kOnly || p.light[size_t(i)]) c.push_back(i);
    if (c.empty()) {
      left_out.push_back(p.name + ": no view has a light file (probes: only)");
      candidates.erase(p.name);
    } else if (wanted_k <= 0) {
      k = k <= 0 ? int(c.size()) : std::min(k, int(c.size()));
    }
  }
  if (candidates.empty()) fail("no plan of split.json can be imported ({})", left_out.empty() ? "none listed" : left_out.front());
  std::vector<ImportView> views;
  for (const SourcePlan& p : plans) {
    if (!candidates.count(p.name)) continue;
    const std::vector<int>& c = candidates[p.name];
    if (int(c.size()) < k) {
      left_out.push_back(fmt::format("{}: {} view(s), fewer than the {} views per scene asked for", p.name, c.size(), k));
      continue;
    }
    for (int j = 0; j < k; ++j) views.push_back({p.name, p.split, c[size_t(j)], j, p.light[size_t(c[size_t(j)])]});
  }
  if (views.empty()) fail_setting("views_per_scene", "no plan of split.json has {} view(s) to import", k);
  *k_out = k;
  return views;
}

// One channel of `image` (clamped to its channels) as a single-channel image; non-finite
// values become 0 and are counted.
Image channel(const Image& image, int c, uint64_t& nonfinite) {
  Image out(image.width, image.height, 1);
  const int from = std::min(c, image.channels - 1);
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const float v = image.at(x, y, from);
      if (!std::isfinite(v)) ++nonfinite;
      out.at(x, y) = std::isfinite(v) ? v : 0.0f;
    }
  return out;
}

Image rgb(const Image& image, uint64_t& nonfinite) {
  Image out(image.width, image.height, 3);
  for (int c = 0; c < 3; ++c) {
    const Image one = channel(image, c, nonfinite);
    for (size_t i = 0; i < one.pixels.size(); ++i) out.pixels[i * 3 + size_t(c)] = one.pixels[i];
  }
  return out;
}

Image read_panorama(const ImportContext& ctx, const fs::path& path) {
  Image image = read_image(path);
  if (image.width != ctx.width || image.height != ctx.height)
    fail("{}: {}x{}, but the first view of the import is {}x{} (a dataset has one panorama size)", path.string(),
         image.width, image.height, ctx.width, ctx.height);
  return image;
}

// Depth in metres and the geometry mask (a surface: finite depth > 0).
void convert_depth(const Image& stored, uint64_t& nonfinite, Image& depth, Image& geometry) {
  depth = channel(stored, fh::kScalarChannel, nonfinite);
  geometry = Image(depth.width, depth.height, 1);
  for (size_t i = 0; i < depth.pixels.size(); ++i) {
    depth.pixels[i] = std::max(0.0f, fh::decode_depth(depth.pixels[i]));
    geometry.pixels[i] = depth.pixels[i] > 0.0f ? 1.0f : 0.0f;
  }
}

// Unit world-space normals in our axes; 0 where there is no surface.
Image convert_normals(const Image& stored, const Image& geometry, const fh::NormalAxes& axes, uint64_t& nonfinite) {
  const Image encoded = rgb(stored, nonfinite);
  Image normal(encoded.width, encoded.height, 3);
  for (int y = 0; y < normal.height; ++y)
    for (int x = 0; x < normal.width; ++x) {
      if (geometry.at(x, y) <= 0.0f) continue;
      glm::vec3 n = axes.to_ours({fh::decode_normal(encoded.at(x, y, 0)), fh::decode_normal(encoded.at(x, y, 1)),
                                  fh::decode_normal(encoded.at(x, y, 2))});
      const float length = glm::length(n);
      n = length > 1e-6f ? n / length : glm::vec3(0.0f);  // below 1e-6: no direction to keep
      for (int c = 0; c < 3; ++c) normal.at(x, y, c) = n[c];
    }
  return normal;
}

// mask_emissive and mask_transparent: from our export's sidecar when there is one; else every
// surface pixel outside FutureHouse's mask is in both (the file does not say which it is).
void convert_masks(const ImportContext& ctx, const ImportView& v, const Image& mask, const Image& geometry,
                   Image& emissive, Image& transparent) {
  const fs::path e = fh::sidecar_path(ctx.src, v.plan, v.source_index, "mask_emissive");
  const fs::path t = fh::sidecar_path(ctx.src, v.plan, v.source_index, "mask_transparent");
  std::error_code ec;
  if (ctx.sidecar && fs::is_regular_file(e, ec) && fs::is_regular_file(t, ec)) {
    uint64_t ignored = 0;
    emissive = channel(read_panorama(ctx, e), 0, ignored);
    transparent = channel(read_panorama(ctx, t), 0, ignored);
    return;
  }
  emissive = Image(mask.width, mask.height, 1);
  for (size_t i = 0; i < mask.pixels.size(); ++i)
    emissive.pixels[i] = geometry.pixels[i] > 0.0f && mask.pixels[i] < fh::kMaskThreshold ? 1.0f : 0.0f;
  transparent = emissive;
}

// probes.exr (the mosaic, as is) and probe_mask.exr (the sidecar's, else every probe valid:
// FutureHouse has no validity map).
void convert_probes(const ImportContext& ctx, const ImportView& v, const fs::path& folder, uint64_t& nonfinite) {
  const fs::path light = fh::light_path(ctx.src, v.plan, v.source_index);
  view::ProbeMosaic probes;
  probes.radiance = rgb(read_image(light), nonfinite);
  const int gh = probes.radiance.height / ctx.probe_height, gw = probes.radiance.width / ctx.probe_width;
  if (probes.radiance.height % ctx.probe_height != 0 || probes.radiance.width % ctx.probe_width != 0 || gh < 1 ||
      gw < 1)
    fail("{}: {}x{} is not a mosaic of {}x{} probes (the import's probe resolution)", light.string(),
         probes.radiance.width, probes.radiance.height, ctx.probe_width, ctx.probe_height);
  if (gh != ctx.grid_height || gw != ctx.grid_width)
    fail("{}: a grid of {}x{} probes, but the first view's is {}x{}", light.string(), gw, gh, ctx.grid_width,
         ctx.grid_height);
  probes.layout = {gh, gw, ctx.probe_height, ctx.probe_width};
  const fs::path side = fh::sidecar_path(ctx.src, v.plan, v.source_index, "probe_mask");
  std::error_code ec;
  probes.mask = Image(gw, gh, 1, 1.0f);
  if (ctx.sidecar && fs::is_regular_file(side, ec)) {
    uint64_t ignored = 0;
    probes.mask = channel(read_image(side), 0, ignored);
    if (probes.mask.width != gw || probes.mask.height != gh)
      fail("{}: {}x{}, but {} is a grid of {}x{} probes", side.string(), probes.mask.width, probes.mask.height,
           light.string(), gw, gh);
  }
  view::write_probe_mosaic(folder, probes);
}

// The view's files under OUT/views/<plan>/vNNN and its record (view.json).
json convert_view(const ImportContext& ctx, const ImportView& v, FacingCount& facing) {
  const std::string id = view_id(v.plan, v.index, ctx.views_per_scene);
  const fs::path rel = view_folder(v.plan, v.index, ctx.views_per_scene);
  const fs::path folder = ctx.out / rel;
  fs::create_directories(folder);
  const auto source = [&](fh::Map map) { return fh::map_path(ctx.src, v.plan, v.source_index, map); };
  uint64_t nonfinite = 0;
  const Image color = rgb(read_panorama(ctx, source(fh::Map::Image)), nonfinite);
  write_image(folder / view::kColorFile, color);
  write_image(folder / view::kBaseColorFile, rgb(read_panorama(ctx, source(fh::Map::Albedo)), nonfinite));
  write_image(folder / view::kRoughnessFile, channel(read_panorama(ctx, source(fh::Map::Roughness)), fh::kScalarChannel, nonfinite));
  write_image(folder / view::kMetalnessFile, channel(read_panorama(ctx, source(fh::Map::Metallic)), fh::kScalarChannel, nonfinite));
  Image depth, geometry, emissive, transparent;
  convert_depth(read_panorama(ctx, source(fh::Map::Depth)), nonfinite, depth, geometry);
  write_image(folder / view::kDepthFile, depth);
  write_image(folder / view::kMaskGeometryFile, geometry);
  const Image normal = convert_normals(read_panorama(ctx, source(fh::Map::Normal)), geometry, ctx.axes, nonfinite);
  write_image(folder / view::kNormalFile, normal);
  const FacingCount f = count_normals_facing_camera(normal, geometry);
  facing.facing += f.facing;
  facing.surface += f.surface;
  const Image mask = channel(read_panorama(ctx, source(fh::Map::Mask)), fh::kScalarChannel, nonfinite);
  convert_masks(ctx, v, mask, geometry, emissive, transparent);
  write_image(folder / view::kMaskEmissiveFile, emissive);
  write_image(folder / view::kMaskTransparentFile, transparent);
  if (ctx.probes) convert_probes(ctx, v, folder, nonfinite);
  const uint64_t seed = view_seed(ctx.seed, v.plan, v.index);
  const InputExposure exposure = choose_input_exposure(color, ctx.input, seed);
  write_input_image(folder / kInputFile, color, exposure, ctx.input);

  std::vector<std::string> names;
  for (const fs::directory_entry& entry : fs::directory_iterator(folder)) names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  json files = json::array();
  for (const std::string& name : names) {
    FileCheck check = inspect_file(folder, name);
    if (!check.problem.empty()) fail("{}: {}", (folder / name).string(), check.problem);
    files.push_back(std::move(check.record));
  }
  const json record = tidy_floats(
      {{"id", id},
       {"scene", {{"name", v.plan}, {"file", (fs::path(fh::kDataFolder) / v.plan).generic_string()}}},
       {"index", v.index},
       {"split", v.split},
       {"dir", rel.generic_string()},
       {"seed", seed},
       {"input", exposure.to_json()},
       {"source",
        {{"format", "futurehouse"},
         {"plan", v.plan},
         {"index", v.source_index},
         {"light", v.light},
         {"nonfinite_values_zeroed", nonfinite},
         {"normals_facing_camera", f.surface ? double(f.facing) / double(f.surface) : 1.0}}},
       {"settings_sha256", ctx.settings_sha256},
       {"files", files}});
  view::write_view_record(folder, record);
  return record;
}

// SRC/phyir/export.json when SRC is one of our exports, else null.
json read_export_record(const fs::path& src) {
  const fs::path path = src / fh::kSidecarFolder / fh::kExportRecordFile;
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) return nullptr;
  const json j = json::parse(read_file(path), nullptr, false);
  if (j.is_discarded() || !j.is_object() || j.value("format", "") != fh::kExportFormat)
    fail("{}: not a {} record", path.string(), fh::kExportFormat);
  return j;
}

// The probe size (flag, else our export's record, else the loader's default) and whether
// probes come in at all.
void choose_probes(const FutureHouseImportOptions& o, const json& record, const std::vector<ImportView>& views,
                   ImportContext& ctx) {
  size_t with_light = 0;
  for (const ImportView& v : views) with_light += v.light ? 1 : 0;
  ctx.probes = o.probes != ImportProbes::kNone && with_light == views.size();
  if (o.probes == ImportProbes::kAuto && with_light > 0 && !ctx.probes)
    spdlog::warn("import-futurehouse: {} of {} views have a light file; importing without probes (probes: only "
             "imports just the views with one)",
             with_light, views.size());
  ctx.probe_height = fh::kProbeHeight;
  ctx.probe_width = fh::kProbeWidth;
  if (record.is_object() && record.contains("probes") && record["probes"].is_object()) {
    ctx.probe_height = record["probes"]["resolution"][0].get<int>();
    ctx.probe_width = record["probes"]["resolution"][1].get<int>();
  }
  if (o.probe_height > 0) ctx.probe_height = o.probe_height;
  if (o.probe_width > 0) ctx.probe_width = o.probe_width;
}

// The probe grid, from the first view's mosaic (every view's must match it).
void choose_grid(ImportContext& ctx, const ImportView& first) {
  const fs::path light = fh::light_path(ctx.src, first.plan, first.source_index);
  const Image mosaic = read_image(light);
  if (mosaic.height % ctx.probe_height != 0 || mosaic.width % ctx.probe_width != 0)
    fail("{}: {}x{} is not a mosaic of {}x{} probes (the probe resolution)", light.string(), mosaic.width,
         mosaic.height, ctx.probe_width, ctx.probe_height);
  ctx.grid_height = mosaic.height / ctx.probe_height;
  ctx.grid_width = mosaic.width / ctx.probe_width;
}

// The manifest's settings: what decided the imported bytes.
json import_settings(const ImportContext& ctx, const fs::path& split_file, const FutureHouseImportOptions& o) {
  DatasetSettings s;
  s.probes = false;
  s.input = o.input;
  json probes = nullptr;
  if (ctx.probes)
    probes = {{"grid", {ctx.grid_height, ctx.grid_width}},
              {"resolution", {ctx.probe_height, ctx.probe_width}},
              {"mosaic", {ctx.grid_height * ctx.probe_height, ctx.grid_width * ctx.probe_width}}};
  const char* probe_mode = o.probes == ImportProbes::kAuto ? "auto" : o.probes == ImportProbes::kNone ? "none" : "only";
  return tidy_floats({{"preset", "futurehouse"},
                      // spp 0: nothing was rendered here (readers such as `dataset stats` expect the key)
                      {"render",
                       {{"projection", "equirect"}, {"width", ctx.width}, {"height", ctx.height}, {"spp", 0}, {"aovs", true}}},
                      {"probes", probes},
                      {"input", s.to_json()["input"]},
                      {"views_per_scene", ctx.views_per_scene},
                      {"seed", ctx.seed},
                      {"source",
                       {{"format", "futurehouse"},
                        {"split_sha256", sha256_file(split_file)},
                        {"normal_axes", ctx.axes.name()},
                        {"phyir_export", ctx.sidecar},
                        {"probes", probe_mode}}}});
}

Manifest import_manifest(const ImportContext& ctx, const json& settings, const std::string& scenes_dir,
                         const std::vector<ImportView>& views, std::vector<json> records) {
  Manifest m;
  m.settings = settings;
  m.scenes_dir = scenes_dir;
  m.shard = {0, 1};
  for (const ImportView& v : views) {
    if (v.index != 0) continue;
    m.scene_names.push_back(v.plan);
    m.scenes.push_back({{"name", v.plan},
                        {"file", (fs::path(fh::kDataFolder) / v.plan).generic_string()},
                        {"split", v.split},
                        {"views", ctx.views_per_scene}});
  }
  m.views = std::move(records);
  return m;
}

// Converts every view in parallel; the first failure (naming the view) ends the import.
std::vector<json> convert_views(const ImportContext& ctx, const std::vector<ImportView>& views,
                                const FutureHouseImportOptions& o, FacingCount& facing) {
  const int n = o.threads > 0 ? o.threads : tbb::info::default_concurrency();
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, n);
  Progress progress("import-futurehouse", views.size(), "views", o.progress);
  std::vector<json> records(views.size());
  std::mutex mutex;
  std::string first_error;
  tbb::parallel_for(size_t(0), views.size(), [&](size_t i) {
    FacingCount f;
    try {
      records[i] = convert_view(ctx, views[i], f);
    } catch (const std::exception& e) {
      std::lock_guard<std::mutex> lock(mutex);
      if (first_error.empty()) first_error = fmt::format("plan {} view {}: {}", views[i].plan, views[i].source_index, e.what());
    }
    {
      std::lock_guard<std::mutex> lock(mutex);
      facing.facing += f.facing;
      facing.surface += f.surface;
    }
    progress.advance();
  });
  progress.finish();
  if (!first_error.empty()) fail("import-futurehouse {}: {}", o.src.string(), first_error);
  return records;
}

}  // namespace

FacingCount count_normals_facing_camera(const Image& normal, const Image& geometry) {
  FacingCount count;
  for (int y = 0; y < normal.height; ++y)
    for (int x = 0; x < normal.width; ++x) {
      if (geometry.at(x, y) <= 0.0f) continue;
      const glm::vec3 d = equirect_direction({(x + 0.5f) / normal.width, (y + 0.5f) / normal.height});
      const glm::vec3 n(normal.at(x, y, 0), normal.at(x, y, 1), normal.at(x, y, 2));
      ++count.surface;
      count.facing += glm::dot(n, d) < 0.0f ? 1 : 0;
    }
  return count;
}

FutureHouseImportSummary import_futurehouse(const FutureHouseImportOptions& o) {
  std::error_code ec;
  if (!fs::is_directory(o.src / fh::kDataFolder, ec))
    fail("{}: no {} folder (the FutureHouse release's per-view maps)", o.src.string(), fh::kDataFolder);
  const fs::path split_file = o.split_file.empty() ? o.src / fh::kSplitFile : o.split_file;
  const std::map<std::string, std::string> split_of = read_split(split_file);
  const json record = read_export_record(o.src);
  FutureHouseImportSummary summary;
  std::vector<SourcePlan> plans;
  for (const auto& [name, split] : split_of) {
    plans.push_back(scan_plan(o.src, name, split));
    if (!plans.back().problem.empty()) summary.left_out.push_back(name + ": " + plans.back().problem);
  }
  ImportContext ctx;
  const std::vector<ImportView> views = choose_views(plans, o.probes, o.views_per_scene, &ctx.views_per_scene, summary.left_out);
  ctx.src = o.src;
  ctx.axes = fh::NormalAxes::parse(!o.normal_axes.empty()  ? o.normal_axes
                                   : record.is_object()    ? record.value("normal_axes", "x,y,z")
                                                           : "x,y,z");
  ctx.sidecar = record.is_object();
  ctx.input = o.input;
  ctx.seed = o.seed;
  const fs::path first = fh::map_path(o.src, views[0].plan, views[0].source_index, fh::Map::Image);
  const Image image = read_image(first);
  if (image.width != 2 * image.height)
    fail("{}: {}x{} is not a 2:1 equirectangular panorama", first.string(), image.width, image.height);
  ctx.width = image.width;
  ctx.height = image.height;
  choose_probes(o, record, views, ctx);
  if (ctx.probes) choose_grid(ctx, views[0]);
  const json settings = import_settings(ctx, split_file, o);
  ctx.settings_sha256 = sha256_hex(settings.dump());

  PartialFolder folder(o.out);
  ctx.out = folder.path();
  FacingCount facing;
  std::vector<json> records = convert_views(ctx, views, o, facing);
  write_file_atomic(ctx.out / kSettingsFile, json{{"format", kManifestFormat},
                                                  {"generator", std::string("phyir ") + PHYIR_VERSION},
                                                  {"settings", settings}}.dump(2) + "\n");
  const Manifest m = import_manifest(ctx, settings, o.src.generic_string(), views, std::move(records));
  write_manifest(ctx.out, m);
  folder.commit();

  summary.plans = m.scenes.size();
  summary.views = m.views.size();
  summary.probes = ctx.probes;
  summary.normals_facing_camera = facing.surface ? double(facing.facing) / double(facing.surface) : 1.0;
  return summary;
}

}  // namespace phyir::dataset
