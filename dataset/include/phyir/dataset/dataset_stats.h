#pragma once
// `phyir dataset stats DIR`: what a finished dataset holds, in numbers a person can read.
//
// - Views per split and per scene (from manifest.json).
// - Material mix from each view's AOVs, as fractions of all panorama pixels. Every pixel is
//   in exactly one class, in this order: no geometry (mask_geometry < 0.5), emissive
//   (mask_emissive > 0.5), transparent (mask_transparent > 0.5), then opaque surfaces by
//   roughness R: mirror (R < 0.05), glossy (0.05 <= R < 0.5), diffuse (R >= 0.5). Metal
//   (metalness > 0.5) is counted over the opaque surfaces, across the three roughness classes.
//   Fractions are of pixels, not solid angle (equirectangular rows near the poles count as
//   much as the horizon).
// - Light levels: luminance Y = 0.2126 R + 0.7152 G + 0.0722 B of color.exr over all pixels
//   (mean exact; percentiles from a histogram of log10 Y with 100 bins per decade, so within
//   1.2 %); the input's exposure (manifest: exposure_stops) and the fraction of input.png
//   pixels with a channel at 1.0 (clipped).
// - Render cost: each view's timing.json (wall seconds of the view, its colour and probe
//   passes, threads) and the manifest's ray counts.
//
// Pixel statistics read seven files per view; `max_views` limits them to an evenly spaced
// sample for huge datasets. Results do not depend on the thread count.
#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace phyir::dataset {

inline constexpr float kMirrorRoughness = 0.05f;  // below: mirror
inline constexpr float kGlossyRoughness = 0.5f;   // below (and not mirror): glossy
inline constexpr float kMetalThreshold = 0.5f;    // metalness above: metal

struct StatsOptions {
  size_t max_views = 0;  // views whose pixels are read: 0 = all, else an evenly spaced sample
  int threads = 0;       // 0 = all cores
  bool progress = true;
};

// Pixel counts of the classes above.
struct MaterialCounts {
  uint64_t pixels = 0;
  uint64_t no_geometry = 0, emissive = 0, transparent = 0, mirror = 0, glossy = 0, diffuse = 0;
  uint64_t metal = 0;  // opaque surfaces with metalness > 0.5
  double fraction(uint64_t n) const { return pixels ? double(n) / double(pixels) : 0.0; }
};

// Summary of a sequence of values: count, mean, min, median, max.
struct Summary {
  size_t count = 0;
  double mean = 0, min = 0, median = 0, max = 0, total = 0;
  static Summary of(std::vector<double> values);
};

struct DatasetStats {
  std::filesystem::path dir;
  std::string preset;
  int width = 0, height = 0, spp = 0;
  bool probes = false;
  int probe_grid[2] = {0, 0}, probe_res[2] = {0, 0};
  size_t scenes = 0, views = 0;
  std::map<std::string, size_t> views_per_split, scenes_per_split;
  std::map<std::string, size_t> views_per_scene;

  size_t views_measured = 0;  // views whose pixels were read
  MaterialCounts material;
  double luminance_mean = 0, luminance_max = 0;
  std::map<std::string, double> luminance_percentiles;  // "p1", "p5", "p50", "p95", "p99"
  Summary exposure_stops;     // over all views (manifest)
  double input_clipped = 0;   // fraction of input.png pixels of the measured views

  Summary view_seconds, color_seconds, probe_seconds;  // views that have a timing.json
  Summary threads;
  Summary rays, probe_rays;  // per view (manifest)
};

// Throws phyir::Error naming the file when there is no readable manifest or a view's files
// cannot be read.
DatasetStats compute_dataset_stats(const std::filesystem::path& dir, const StatsOptions& options = {});

// The summary as lines of text, and as JSON (`phyir dataset stats` writes it on request).
std::string format_stats(const DatasetStats& stats);
nlohmann::json stats_to_json(const DatasetStats& stats);

// A contact sheet of sample views: input.png thumbnails (thumb_width wide, the panorama's
// aspect) of up to `count` views evenly spaced in the manifest, `columns` per row, each
// captioned with its id and split. Written atomically as PNG (or any format OIIO writes).
struct ContactSheetOptions {
  int count = 12;
  int columns = 4;
  int thumb_width = 256;
};
void write_contact_sheet(const std::filesystem::path& dir, const std::filesystem::path& out,
                         const ContactSheetOptions& options = {});

}  // namespace phyir::dataset
