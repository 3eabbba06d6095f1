#include "phyir/dataset/dataset_stats.h"

#include "phyir/view/input_exposure.h"

#include <tbb/combinable.h>
#include <tbb/global_control.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "phyir/core/atomic_file.h"
#include "phyir/core/error.h"
#include "phyir/core/image_io.h"
#include "phyir/core/log.h"
#include "phyir/core/progress.h"
#include "phyir/dataset/layout.h"
#include "phyir/dataset/manifest.h"
#include "phyir/view/view_files.h"

namespace phyir::dataset {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// log10 luminance histogram: bin 0 holds Y < 1e-6 (black included), the last Y >= 1e6.
constexpr double kLogMin = -6.0, kLogMax = 6.0;
constexpr int kBinsPerDecade = 100;
constexpr int kBins = int((kLogMax - kLogMin) * kBinsPerDecade) + 2;

int luminance_bin(double y) {
  if (!(y >= std::pow(10.0, kLogMin))) return 0;
  const double b = (std::log10(y) - kLogMin) * kBinsPerDecade;
  return std::min(kBins - 1, 1 + int(std::floor(b)));
}
double bin_centre(int bin) {
  if (bin == 0) return 0.0;
  return std::pow(10.0, kLogMin + (bin - 1 + 0.5) / kBinsPerDecade);
}

// Counts of one thread's views; integers, so merging in any order gives the same result.
struct Accumulator {
  MaterialCounts material;
  std::vector<uint64_t> histogram = std::vector<uint64_t>(kBins, 0);
  uint64_t input_pixels = 0, input_clipped = 0;
  double luminance_max = 0;
};

Image read_map(const fs::path& dir, const char* name, int width, int height) {
  const fs::path path = dir / name;
  Image image = read_image(path);
  if (image.width != width || image.height != height)
    fail("{}: {}x{}, but color.exr is {}x{}", path.string(), image.width, image.height, width, height);
  return image;
}

// One view's pixels into `acc`; returns the sum of its luminance.
double measure_view(const fs::path& dir, Accumulator& acc) {
  const Image color = read_image(dir / view::kColorFile);
  const int W = color.width, H = color.height;
  if (color.channels < 3) fail("{}: {} channels, expected RGB", (dir / view::kColorFile).string(), color.channels);
  const Image geometry = read_map(dir, view::kMaskGeometryFile, W, H);
  const Image emissive = read_map(dir, view::kMaskEmissiveFile, W, H);
  const Image transparent = read_map(dir, view::kMaskTransparentFile, W, H);
  const Image roughness = read_map(dir, view::kRoughnessFile, W, H);
  const Image metalness = read_map(dir, view::kMetalnessFile, W, H);
  MaterialCounts& m = acc.material;
  double sum = 0;
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      ++m.pixels;
      const double lum = 0.2126 * color.at(x, y, 0) + 0.7152 * color.at(x, y, 1) + 0.0722 * color.at(x, y, 2);
      sum += lum;
      acc.luminance_max = std::max(acc.luminance_max, lum);
      ++acc.histogram[size_t(luminance_bin(lum))];
      if (!(geometry.at(x, y) >= 0.5f)) {
        ++m.no_geometry;
      } else if (emissive.at(x, y) > 0.5f) {
        ++m.emissive;
      } else if (transparent.at(x, y) > 0.5f) {
        ++m.transparent;
      } else {
        const float r = roughness.at(x, y);
        if (r < kMirrorRoughness) ++m.mirror;
        else if (r < kGlossyRoughness) ++m.glossy;
        else ++m.diffuse;
        if (metalness.at(x, y) > kMetalThreshold) ++m.metal;
      }
    }
  // The network's input: pixels with a channel at full scale lost their highlight.
  const Image input = read_image(dir / kInputFile);
  for (int y = 0; y < input.height; ++y)
    for (int x = 0; x < input.width; ++x) {
      ++acc.input_pixels;
      bool clipped = false;
      for (int c = 0; c < std::min(3, input.channels); ++c) clipped = clipped || input.at(x, y, c) >= 1.0f;
      acc.input_clipped += clipped;
    }
  return sum;
}

// Evenly spaced indices: k * n / count.
std::vector<size_t> sample_indices(size_t n, size_t count) {
  std::vector<size_t> out;
  if (count == 0 || count >= n) {
    for (size_t i = 0; i < n; ++i) out.push_back(i);
    return out;
  }
  for (size_t k = 0; k < count; ++k) out.push_back(k * n / count);
  return out;
}

double number(const json& j, std::initializer_list<const char*> path) {
  const json* at = &j;
  for (const char* key : path) {
    if (!at->is_object() || !at->contains(key)) return NAN;
    at = &(*at)[key];
  }
  return at->is_number() ? at->get<double>() : NAN;
}

json summary_json(const Summary& s) {
  if (s.count == 0) return nullptr;
  return {{"count", s.count}, {"mean", s.mean}, {"min", s.min}, {"median", s.median}, {"max", s.max}, {"total", s.total}};
}

std::string percent(double f) { return fmt::format("{:5.1f} %", 100.0 * f); }

std::string si(double v) {
  if (v >= 1e9) return fmt::format("{:.2f} G", v / 1e9);
  if (v >= 1e6) return fmt::format("{:.2f} M", v / 1e6);
  if (v >= 1e3) return fmt::format("{:.1f} k", v / 1e3);
  return fmt::format("{:.0f}", v);
}

std::string duration(double s) {
  if (s < 120) return fmt::format("{:.1f} s", s);
  if (s < 7200) return fmt::format("{:.1f} min", s / 60);
  return fmt::format("{:.1f} h", s / 3600);
}

}  // namespace

Summary Summary::of(std::vector<double> values) {
  values.erase(std::remove_if(values.begin(), values.end(), [](double v) { return !std::isfinite(v); }), values.end());
  Summary s;
  s.count = values.size();
  if (values.empty()) return s;
  std::sort(values.begin(), values.end());
  for (double v : values) s.total += v;  // ascending: the same sum whatever the input order
  s.mean = s.total / double(values.size());
  s.min = values.front();
  s.max = values.back();
  const size_t n = values.size();
  s.median = n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
  return s;
}

namespace {

// The header: resolution, probes, scenes and views per split.
void read_settings(const Manifest& manifest, DatasetStats& st) {
  const json& settings = manifest.settings;
  st.preset = settings.value("preset", "");
  st.width = int(number(settings, {"render", "width"}));
  st.height = int(number(settings, {"render", "height"}));
  st.spp = int(number(settings, {"render", "spp"}));
  if (settings.contains("probes") && settings["probes"].is_object()) {
    st.probes = true;
    for (int i = 0; i < 2; ++i) {
      st.probe_grid[i] = settings["probes"].value("grid", json::array({0, 0}))[size_t(i)].get<int>();
      st.probe_res[i] = settings["probes"].value("resolution", json::array({0, 0}))[size_t(i)].get<int>();
    }
  }
  for (const json& scene : manifest.scenes) ++st.scenes_per_split[scene.value("split", "?")];
  st.scenes = manifest.scenes.size();
  st.views = manifest.views.size();
}

// Exposure and rays from the view records; wall-clock figures from each view's timing.json
// (they live outside the manifest: they differ between runs).
void read_view_records(const fs::path& dir, const Manifest& manifest, DatasetStats& st) {
  std::vector<double> exposure, rays, probe_rays;
  std::vector<double> view_seconds, color_seconds, probe_seconds, threads;
  for (const json& v : manifest.views) {
    ++st.views_per_split[v.value("split", "?")];
    ++st.views_per_scene[v.at("scene").value("name", "?")];
    const view::InputExposure input = view::InputExposure::from_json(v.value("input", json()), kManifestFile);
    exposure.push_back(input.recorded ? input.stops : NAN);
    rays.push_back(number(v, {"render", "counters", "rays_traced"}));
    probe_rays.push_back(number(v, {"render", "probes", "rays"}));
    const fs::path timing_path = dir / v.value("dir", "") / kTimingFile;
    std::error_code ec;
    if (!fs::is_regular_file(timing_path, ec)) continue;
    const json timing = json::parse(read_file(timing_path), nullptr, false);
    if (timing.is_discarded()) {
      spdlog::warn("{}: not valid JSON; left out of the render cost", timing_path.string());
      continue;
    }
    view_seconds.push_back(number(timing, {"view_seconds"}));
    color_seconds.push_back(number(timing, {"timings", "color_seconds"}));
    probe_seconds.push_back(number(timing, {"timings", "probe_seconds"}));
    threads.push_back(number(timing, {"settings", "threads"}));
  }
  st.exposure_stops = Summary::of(exposure);
  st.rays = Summary::of(rays);
  st.probe_rays = Summary::of(probe_rays);
  st.view_seconds = Summary::of(view_seconds);
  st.color_seconds = Summary::of(color_seconds);
  st.probe_seconds = Summary::of(probe_seconds);
  st.threads = Summary::of(threads);
}

void add(Accumulator& total, const Accumulator& a) {
  MaterialCounts& m = total.material;
  m.pixels += a.material.pixels;
  m.no_geometry += a.material.no_geometry;
  m.emissive += a.material.emissive;
  m.transparent += a.material.transparent;
  m.mirror += a.material.mirror;
  m.glossy += a.material.glossy;
  m.diffuse += a.material.diffuse;
  m.metal += a.material.metal;
  for (int b = 0; b < kBins; ++b) total.histogram[size_t(b)] += a.histogram[size_t(b)];
  total.input_pixels += a.input_pixels;
  total.input_clipped += a.input_clipped;
  total.luminance_max = std::max(total.luminance_max, a.luminance_max);
}

// Percentile p: the first bin where the cumulative count reaches p of the pixels.
void luminance_percentiles(const Accumulator& total, DatasetStats& st) {
  for (const auto& [name, p] : std::vector<std::pair<std::string, double>>{
           {"p1", 0.01}, {"p5", 0.05}, {"p50", 0.5}, {"p95", 0.95}, {"p99", 0.99}}) {
    if (total.material.pixels == 0) break;
    const double want = p * double(total.material.pixels);
    uint64_t cumulative = 0;
    for (int b = 0; b < kBins; ++b) {
      cumulative += total.histogram[size_t(b)];
      if (double(cumulative) >= want) {
        st.luminance_percentiles[name] = b == kBins - 1 ? st.luminance_max : bin_centre(b);
        break;
      }
    }
  }
}

// The pixels of a sample of views: material mix, luminance, clipping.
void measure_pixels(const fs::path& dir, const Manifest& manifest, const StatsOptions& o, DatasetStats& st) {
  const std::vector<size_t> sample = sample_indices(manifest.views.size(), o.max_views);
  const int n_threads = o.threads > 0 ? o.threads : tbb::info::default_concurrency();
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(n_threads));
  tbb::combinable<Accumulator> partial;
  std::vector<double> sums(sample.size(), 0.0);
  {
    Progress progress("stats", sample.size(), "views", o.progress);
    tbb::parallel_for(size_t(0), sample.size(), [&](size_t i) {
      const json& v = manifest.views[sample[i]];
      sums[i] = measure_view(dir / v.value("dir", ""), partial.local());
      progress.advance();
    });
  }
  Accumulator total;
  partial.combine_each([&](const Accumulator& a) { add(total, a); });
  st.views_measured = sample.size();
  st.material = total.material;
  double sum = 0;
  for (double s : sums) sum += s;  // in view order: independent of the threads
  st.luminance_mean = total.material.pixels ? sum / double(total.material.pixels) : 0.0;
  st.luminance_max = total.luminance_max;
  st.input_clipped = total.input_pixels ? double(total.input_clipped) / double(total.input_pixels) : 0.0;
  luminance_percentiles(total, st);
}

}  // namespace

DatasetStats compute_dataset_stats(const fs::path& dir, const StatsOptions& o) {
  const Manifest manifest = read_manifest(dir);
  DatasetStats st;
  st.dir = dir;
  read_settings(manifest, st);
  read_view_records(dir, manifest, st);
  measure_pixels(dir, manifest, o, st);
  return st;
}

std::string format_stats(const DatasetStats& s) {
  std::string out;
  const auto line = [&](const std::string& text) { out += text + "\n"; };
  std::string probes = "no probes";
  if (s.probes)
    probes = fmt::format("probes {}x{} of {}x{}", s.probe_grid[0], s.probe_grid[1], s.probe_res[0], s.probe_res[1]);
  line(fmt::format("dataset {}: preset {}, {}x{}, {} spp, {}", s.dir.string(), s.preset, s.width, s.height, s.spp,
                   probes));
  line(fmt::format("  {} scenes, {} views", s.scenes, s.views));
  std::string splits;
  for (const char* split : {"train", "val", "test"})
    splits += fmt::format("{}{} {} views ({} scenes)", splits.empty() ? "" : ", ", split,
                          s.views_per_split.count(split) ? s.views_per_split.at(split) : 0,
                          s.scenes_per_split.count(split) ? s.scenes_per_split.at(split) : 0);
  line("  splits: " + splits);
  std::map<size_t, size_t> scenes_with;  // views -> scenes with that many
  for (const auto& [scene, n] : s.views_per_scene) ++scenes_with[n];
  std::string per_scene;
  for (const auto& [n, scenes] : scenes_with)
    per_scene += fmt::format("{}{} scene(s) with {} views", per_scene.empty() ? "" : ", ", scenes, n);
  line("  per scene: " + per_scene);

  const MaterialCounts& m = s.material;
  line(fmt::format("material mix ({} views, {} pixels; fractions of pixels):", s.views_measured, m.pixels));
  line("  no geometry  " + percent(m.fraction(m.no_geometry)));
  line("  emissive     " + percent(m.fraction(m.emissive)));
  line("  transparent  " + percent(m.fraction(m.transparent)));
  line("  mirror       " + percent(m.fraction(m.mirror)) + "   opaque, roughness < 0.05");
  line("  glossy       " + percent(m.fraction(m.glossy)) + "   opaque, roughness 0.05 - 0.5");
  line("  diffuse      " + percent(m.fraction(m.diffuse)) + "   opaque, roughness >= 0.5");
  line("  metal        " + percent(m.fraction(m.metal)) + "   opaque, metalness > 0.5 (any roughness)");

  line("light (luminance of color.exr, linear):");
  std::string pct;
  for (const char* p : {"p1", "p5", "p50", "p95", "p99"})
    if (s.luminance_percentiles.count(p)) pct += fmt::format(", {} {:.4g}", p, s.luminance_percentiles.at(p));
  line(fmt::format("  mean {:.4g}{}, max {:.4g}", s.luminance_mean, pct, s.luminance_max));
  if (s.exposure_stops.count)
    line(fmt::format("  input exposure: mean {:+.2f} stops (min {:+.2f}, max {:+.2f}); clipped input pixels {}",
                     s.exposure_stops.mean, s.exposure_stops.min, s.exposure_stops.max,
                     fmt::format("{:.1f} %", 100.0 * s.input_clipped)));

  line(fmt::format("render cost ({} of {} views have a timing.json):", s.view_seconds.count, s.views));
  if (s.view_seconds.count) {
    line(fmt::format("  wall seconds per view: mean {:.2f}, median {:.2f}, max {:.2f} (all views: {}), {:.0f} threads",
                     s.view_seconds.mean, s.view_seconds.median, s.view_seconds.max, duration(s.view_seconds.total),
                     s.threads.mean));
    std::string parts = fmt::format("  of which colour {:.2f} s", s.color_seconds.mean);
    if (s.probe_seconds.count) parts += fmt::format(", probes {:.2f} s", s.probe_seconds.mean);
    line(parts + " (means; views in flight share the threads)");
  }
  if (s.rays.count) {
    std::string rays = fmt::format("  rays per view: {} (panorama)", si(s.rays.mean));
    if (s.probe_rays.count) rays += fmt::format(", {} (probes)", si(s.probe_rays.mean));
    line(rays);
  }
  return out;
}

json stats_to_json(const DatasetStats& s) {
  const MaterialCounts& m = s.material;
  json splits = json::object();
  for (const auto& [split, n] : s.views_per_split)
    splits[split] = {{"views", n}, {"scenes", s.scenes_per_split.count(split) ? s.scenes_per_split.at(split) : 0}};
  return {
      {"dataset", s.dir.generic_string()},
      {"settings",
       {{"preset", s.preset},
        {"width", s.width},
        {"height", s.height},
        {"spp", s.spp},
        {"probes", s.probes ? json{{"grid", {s.probe_grid[0], s.probe_grid[1]}},
                                   {"resolution", {s.probe_res[0], s.probe_res[1]}}}
                            : json(nullptr)}}},
      {"scenes", s.scenes},
      {"views", s.views},
      {"splits", splits},
      {"views_per_scene", s.views_per_scene},
      {"material",
       {{"views_measured", s.views_measured},
        {"pixels", m.pixels},
        {"thresholds", {{"mirror_roughness", kMirrorRoughness}, {"glossy_roughness", kGlossyRoughness},
                        {"metalness", kMetalThreshold}}},
        {"fractions",
         {{"no_geometry", m.fraction(m.no_geometry)},
          {"emissive", m.fraction(m.emissive)},
          {"transparent", m.fraction(m.transparent)},
          {"mirror", m.fraction(m.mirror)},
          {"glossy", m.fraction(m.glossy)},
          {"diffuse", m.fraction(m.diffuse)},
          {"metal", m.fraction(m.metal)}}}}},
      {"light",
       {{"luminance_mean", s.luminance_mean},
        {"luminance_max", s.luminance_max},
        {"luminance_percentiles", s.luminance_percentiles},
        {view::kExposureStopsKey, summary_json(s.exposure_stops)},
        {"input_clipped_fraction", s.input_clipped}}},
      {"render_cost",
       {{"view_seconds", summary_json(s.view_seconds)},
        {"color_seconds", summary_json(s.color_seconds)},
        {"probe_seconds", summary_json(s.probe_seconds)},
        {"threads", summary_json(s.threads)},
        {"rays_per_view", summary_json(s.rays)},
        {"probe_rays_per_view", summary_json(s.probe_rays)}}},
  };
}

void write_contact_sheet(const fs::path& dir, const fs::path& out, const ContactSheetOptions& o) {
  namespace oiio = OIIO;
  if (o.count <= 0 || o.columns <= 0 || o.thumb_width < 8)
    fail("contact sheet: count and columns must be positive and thumbnails at least 8 pixels wide");
  const Manifest manifest = read_manifest(dir);
  if (manifest.views.empty()) fail("{}: the manifest lists no views", (dir / kManifestFile).string());
  const std::vector<size_t> picks = sample_indices(manifest.views.size(), size_t(o.count));
  const int aspect_w = std::max(1, int(number(manifest.settings, {"render", "width"})));
  const int aspect_h = std::max(1, int(number(manifest.settings, {"render", "height"})));
  const int tw = o.thumb_width, th = std::max(1, tw * aspect_h / aspect_w);
  const int pad = 4, caption = 18;
  const int columns = std::min(o.columns, int(picks.size()));
  const int rows = (int(picks.size()) + columns - 1) / columns;
  const int W = pad + columns * (tw + pad), H = pad + rows * (th + caption + pad);
  oiio::ImageBuf sheet(oiio::ImageSpec(W, H, 3, oiio::TypeDesc::FLOAT));
  const float background[3] = {0.12f, 0.12f, 0.12f};
  oiio::ImageBufAlgo::fill(sheet, background);
  bool labels = true;
  for (size_t k = 0; k < picks.size(); ++k) {
    const json& v = manifest.views[picks[k]];
    const fs::path input = dir / v.value("dir", "") / kInputFile;
    const Image image = read_image(input);  // names the file on failure
    oiio::ImageBuf source(oiio::ImageSpec(image.width, image.height, image.channels, oiio::TypeDesc::FLOAT),
                          const_cast<float*>(image.pixels.data()));
    oiio::ImageBuf thumb;
    if (!oiio::ImageBufAlgo::resize(thumb, source, "", 0.0f, oiio::ROI(0, tw, 0, th, 0, 1, 0, image.channels)))
      fail("{}: cannot resize: {}", input.string(), thumb.geterror());
    const int x = pad + int(k % size_t(columns)) * (tw + pad), y = pad + int(k / size_t(columns)) * (th + caption + pad);
    if (image.channels == 1) thumb = oiio::ImageBufAlgo::channels(thumb, 3, {0, 0, 0});
    else if (image.channels > 3) thumb = oiio::ImageBufAlgo::channels(thumb, 3, {0, 1, 2});
    oiio::ImageBufAlgo::paste(sheet, x, y, 0, 0, thumb);
    if (labels) {
      const std::string text = v.value("id", "?") + "  " + v.value("split", "");
      const float white[3] = {0.9f, 0.9f, 0.9f};
      // Needs a font OIIO can find (Debian: fonts-dejavu-core); without one the sheet is unlabelled.
      labels = oiio::ImageBufAlgo::render_text(sheet, x + 2, y + th + 13, text, 12, "DejaVuSans", white,
                                               oiio::ImageBufAlgo::TextAlignX::Left,
                                               oiio::ImageBufAlgo::TextAlignY::Baseline, 0,
                                               oiio::ROI(x, x + tw, y + th, y + th + caption, 0, 1, 0, 3));
      if (!labels) spdlog::warn("contact sheet: no labels ({})", sheet.geterror());
    }
  }
  Image result(W, H, 3);
  if (!sheet.get_pixels(oiio::ROI(0, W, 0, H, 0, 1, 0, 3), oiio::TypeDesc::FLOAT, result.pixels.data()))
    fail("contact sheet: {}", sheet.geterror());
  write_image(out, result);
}

}  // namespace phyir::dataset
