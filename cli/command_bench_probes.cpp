// phyir bench probes: what per-pixel light probes cost and how wrong they are, per mode and
// setting, against a converged reference (docs/probes.md has the method and the results).
//
// The reference is the unbiased path mode at --reference-spp on a random subset of
// --reference-probes valid probes, rendered as two independent halves so that its own noise
// is measured too (reference_noise = RMSE(half 1 - half 2) / 2, relative like the errors).
// Each configuration "MODE:SPP[:CACHE_SPP[:CELL_M[:SEED[:DIRECT_CELLS[:SPREAD]]]]]" is then timed and compared on that
// subset: cache mode renders the full grid (its cache depends on every probe); path mode
// renders the subset only and its time is scaled to the full grid's probe count (its
// probes are independent; the row says `extrapolated`).
#include <tbb/global_control.h>
#include <tbb/info.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <cmath>
#include <map>
#include <memory>
#include <optional>
#include <sstream>

#include "bench_suite_runner.h"
#include "commands.h"
#include "phyir/core/atomic_file.h"
#include "phyir/core/error.h"
#include "phyir/core/machine.h"
#include "phyir/core/image_error.h"
#include "phyir/core/image_io.h"
#include "phyir/core/log.h"
#include "phyir/render/effects.h"
#include "phyir/render/environment_light.h"
#include "phyir/render/probe_grid.h"
#include "phyir/render/probe_renderer.h"
#include "phyir/render/render_job.h"
#include "phyir/render/rng.h"
#include "phyir/scenes/gltf_loader.h"

namespace phyir::cli {

namespace fs = std::filesystem;

namespace {

struct BenchProbeFlags {
  std::string scene;
  std::string suite;                 // suite.json: measure on every scene of it instead
  std::optional<glm::vec3> camera;   // from the suite; else the scene's camera
  std::string out = "bench-probes";
  std::string grid = "128x256";
  std::vector<std::string> res_list = {"16x32"};
  // The settings of docs/probes.md's table.
  std::vector<std::string> configs = {"cache:2:32", "cache:4:64", "cache:4:256", "cache:8:64",
                                      "path:4",     "path:16",    "path:64"};
  int reference_spp = 16384;  // relative noise 1.2% on the mini room (docs/probes.md)
  int reference_probes = 16;
  std::vector<int> probe_indices;  // explicit subset instead of a random one (to study one probe)
  bool subset_only = false;        // cache mode too renders only the subset (its cache then sees only it)
  int threads = 0;
  int max_bounces = 8;
  uint64_t seed = 0;
  float offset = 0.01f;
  int photons = render::ProbeSettings().photons_per_light;
  int width = 512;
  int height = 256;
};

struct Config {
  std::string text;
  render::ProbeMode mode;
  int spp;
  int cache_spp = 128;
  float cache_cell = 0.05f;
  uint64_t seed_offset = 0;  // another run of the same setting, to tell noise from bias
  float direct_cells = 6.0f;
  float spread = 0.75f;
  int share_radius = 1;
  float share_parallax = 0.5f;
};

constexpr const char* kConfigSyntax =
    "MODE:SPP[:CACHE_SPP[:CELL_M[:SEED[:DIRECT_CELLS[:SPREAD[:SHARE_RADIUS[:SHARE_PARALLAX]]]]]]]";

Config parse_config(const std::string& text, const render::ProbeSettings& defaults) {
  Config c{text, render::ProbeMode::kCache, 0, defaults.cache.samples_per_cell, defaults.cache.cell_size, 0, defaults.cache.direct_distance_cells,
           defaults.spread_threshold, defaults.sharing.radius, defaults.sharing.parallax_texels};
  std::vector<std::string> parts;
  std::stringstream in(text);
  for (std::string part; std::getline(in, part, ':');) parts.push_back(part);
  if (parts.size() < 2 || parts.size() > 9) fail("--configs '{}' is not {}", text, kConfigSyntax);
  c.mode = render::parse_probe_mode(parts[0]);
  try {
    c.spp = std::stoi(parts[1]);
    if (parts.size() > 2) c.cache_spp = std::stoi(parts[2]);
    if (parts.size() > 3) c.cache_cell = std::stof(parts[3]);
    if (parts.size() > 4) c.seed_offset = std::stoull(parts[4]);
    if (parts.size() > 5) c.direct_cells = std::stof(parts[5]);
    if (parts.size() > 6) c.spread = std::stof(parts[6]);
    if (parts.size() > 7) c.share_radius = std::stoi(parts[7]);
    if (parts.size() > 8) c.share_parallax = std::stof(parts[8]);
  } catch (const std::exception&) {
    fail("--configs '{}': SPP, CACHE_SPP, CELL_M, SEED, DIRECT_CELLS, SPREAD, SHARE_RADIUS and SHARE_PARALLAX must be numbers",
         text);
  }
  return c;
}

// Two configurations that differ in their seed alone.
bool same_setting(const Config& a, const Config& b) {
  return a.mode == b.mode && a.spp == b.spp && a.cache_spp == b.cache_spp && a.cache_cell == b.cache_cell &&
         a.direct_cells == b.direct_cells && a.spread == b.spread && a.share_radius == b.share_radius &&
         a.share_parallax == b.share_parallax && a.seed_offset != b.seed_offset;
}

// The subset's probes side by side: probe k at columns [k w, (k+1) w).
Image strip(const Image& mosaic, const render::ProbeLayout& layout, const std::vector<int>& subset) {
  Image out(layout.res_width * int(subset.size()), layout.res_height, 3);
  for (size_t k = 0; k < subset.size(); ++k) {
    const Image probe = render::probe_image(mosaic, layout, subset[k] / layout.grid_width, subset[k] % layout.grid_width);
    for (int r = 0; r < layout.res_height; ++r)
      for (int c = 0; c < layout.res_width; ++c)
        for (int ch = 0; ch < 3; ++ch) out.at(int(k) * layout.res_width + c, r, ch) = probe.at(c, r, ch);
  }
  return out;
}

// ---- Where the error is: by texel class, by probe, bias against variance ------------------

// What a measured texel's centre direction sees from its probe's origin; the first class
// that applies (a texel looking back at the probe's own surface is `behind`, near its foot).
enum TexelClass { kSky, kEmitter, kGlass, kGlossy, kBehind, kNear, kFar, kClassCount };
constexpr const char* kClassNames[kClassCount] = {"sky/environment", "emitter", "glass", "glossy (rough < 0.3)",
                                                  "behind (own surface)", "diffuse < 0.5 m", "diffuse >= 0.5 m"};
// Diffuse surfaces nearer than this see the probe's surroundings at large parallax.
constexpr float kNearDistance = 0.5f;

std::vector<int> classify_texels(const render::RenderScene& scene, const std::vector<render::ProbeSite>& sites,
                                 const std::vector<int>& subset, const render::ProbeLayout& layout, float glossy) {
  const int h = layout.res_height, w = layout.res_width;
  std::vector<int> classes(subset.size() * size_t(h * w));
  for (size_t k = 0; k < subset.size(); ++k) {
    const render::ProbeSite& site = sites[size_t(subset[k])];
    for (int r = 0; r < h; ++r) {
      for (int c = 0; c < w; ++c) {
        const glm::vec3 d = render::probe_texel_direction(r, c, h, w, glm::vec2(0.5f));
        render::SurfaceInteraction si;
        int cls = kFar;
        if (!scene.trace(render::Ray{site.origin, d}, &si)) cls = kSky;
        else if (si.emits) cls = kEmitter;
        else if (si.transmission > 0.0f) cls = kGlass;
        else if (si.brdf.roughness < glossy) cls = kGlossy;
        else if (glm::dot(d, site.normal) < 0.0f) cls = kBehind;
        else if (si.distance < kNearDistance) cls = kNear;
        classes[k * size_t(h * w) + size_t(r * w + c)] = cls;
      }
    }
  }
  return classes;
}

// Squared errors of a strip against the reference, summed per texel over channels.
struct TexelErrors {
  std::vector<double> squared;  // per texel (strip pixel)
  double mean_reference = 0.0;  // mean |reference| over texels and channels
};

TexelErrors texel_errors(const Image& a, const Image& reference) {
  TexelErrors e;
  e.squared.assign(size_t(a.width) * size_t(a.height), 0.0);
  double sum_ref = 0.0;
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x)
      for (int ch = 0; ch < 3; ++ch) {
        const double d = double(a.at(x, y, ch)) - double(reference.at(x, y, ch));
        e.squared[size_t(y) * size_t(a.width) + size_t(x)] += d * d;
        sum_ref += std::abs(double(reference.at(x, y, ch)));
      }
  e.mean_reference = sum_ref / (3.0 * double(e.squared.size()));
  return e;
}

// The strip pixel of texel t of subset probe k, as an index into TexelErrors::squared.
size_t strip_index(const render::ProbeLayout& layout, size_t subset_count, size_t k, int t) {
  const int r = t / layout.res_width, c = t % layout.res_width;
  return size_t(r) * size_t(layout.res_width) * subset_count + k * size_t(layout.res_width) + size_t(c);
}

// Error by texel class and by probe: each one's share of the squared error and its RMSE
// relative to the whole subset's mean |reference| (so the classes' squared values add up to
// the total's). With `other` (the same setting, another seed) and the reference's halves, the
// error splits into what does not average away between seeds (bias) and noise.
nlohmann::json error_breakdown(const Image& measured, const Image* other, const Image& reference, const Image halves[2],
                               const std::vector<int>& classes, const std::vector<int>& subset,
                               const std::vector<render::ProbeSite>& sites, const render::ProbeLayout& layout,
                               const render::RenderScene& scene) {
  const TexelErrors e = texel_errors(measured, reference);
  const TexelErrors half = texel_errors(halves[0], halves[1]);
  std::optional<TexelErrors> pair;
  if (other) pair = texel_errors(measured, *other);
  const int texels = layout.texels_per_probe();
  const double n_all = double(e.squared.size()) * 3.0, scale = e.mean_reference;
  double total = 0.0;
  for (double s : e.squared) total += s;
  struct Sum { double err = 0, noise = 0, ref_noise = 0, signed_err = 0, ref = 0; size_t count = 0; };
  std::vector<Sum> per_class(kClassCount), per_probe(subset.size());
  for (size_t k = 0; k < subset.size(); ++k) {
    for (int t = 0; t < texels; ++t) {
      const size_t i = strip_index(layout, subset.size(), k, t);
      const int x = int(i % size_t(measured.width)), y = int(i / size_t(measured.width));
      for (Sum* s : {&per_class[size_t(classes[k * size_t(texels) + size_t(t)])], &per_probe[k]}) {
        s->err += e.squared[i];
        s->ref_noise += half.squared[i] / 4.0;  // the mean of two halves: (h0 - h1)^2 / 4
        if (pair) s->noise += pair->squared[i] / 2.0;  // one run's variance
        for (int ch = 0; ch < 3; ++ch) {
          s->signed_err += double(measured.at(x, y, ch)) - double(reference.at(x, y, ch));
          s->ref += double(reference.at(x, y, ch));
        }
        ++s->count;
      }
    }
  }
  auto describe = [&](const Sum& s) {
    nlohmann::json j = {{"texels", s.count}, {"share_of_squared_error", total > 0 ? s.err / total : 0.0},
                        {"relative_rmse", std::sqrt(s.err / n_all) / scale},
                        {"reference_noise", std::sqrt(s.ref_noise / n_all) / scale},
                        {"mean_error_of_own_mean", s.ref > 0 ? s.signed_err / s.ref : 0.0}};
    if (pair) {
      j["noise"] = std::sqrt(s.noise / n_all) / scale;
      j["bias"] = std::sqrt(std::max(s.err - s.noise - s.ref_noise, 0.0) / n_all) / scale;
    }
    return j;
  };
  nlohmann::json out = {{"classes", nlohmann::json::object()}, {"probes", nlohmann::json::array()}};
  for (int c = 0; c < kClassCount; ++c) out["classes"][kClassNames[c]] = describe(per_class[size_t(c)]);
  for (size_t k = 0; k < subset.size(); ++k) {
    const render::ProbeSite& site = sites[size_t(subset[k])];
    nlohmann::json j = describe(per_probe[k]);
    j["index"] = subset[k];
    j["normal"] = {site.normal.x, site.normal.y, site.normal.z};
    j["nearest_light_m"] = scene.emitters().distance_bound(site.origin);
    out["probes"].push_back(j);
  }
  out["total"] = describe([&] { Sum s; for (const Sum& c : per_class) { s.err += c.err; s.noise += c.noise; s.ref_noise += c.ref_noise; s.signed_err += c.signed_err; s.ref += c.ref; s.count += c.count; } return s; }());
  return out;
}

void log_breakdown(const std::string& config, const nlohmann::json& b) {
  spdlog::info("{}: where the squared error is (share, relative RMSE, bias, noise, mean error):", config);
  auto line = [](const std::string& name, const nlohmann::json& j) {
    spdlog::info("  {:<24} {:>6} texels  {:5.1f}%  rmse {:.4f}  bias {:.4f}  noise {:.4f}  mean {:+.4f}", name,
                 j["texels"].get<size_t>(), 100.0 * j["share_of_squared_error"].get<double>(),
                 j["relative_rmse"].get<double>(), j.value("bias", -1.0), j.value("noise", -1.0),
                 j["mean_error_of_own_mean"].get<double>());
  };
  for (const auto& [name, j] : b["classes"].items()) line(name, j);
  for (const auto& j : b["probes"]) {
    // A scene without emissive triangles or punctual lights at a distance (the sun) has none.
    const float light_m = j["nearest_light_m"].is_number() ? j["nearest_light_m"].get<float>() : -1.0f;
    const std::string light = std::isfinite(light_m) && light_m >= 0.0f
                                  ? "light " + std::to_string(int(100.0f * light_m)) + " cm"
                                  : "no light near";
    line("probe " + std::to_string(j["index"].get<int>()) + " (" + light + ")", j);
  }
}

void run_bench_probes(const BenchProbeFlags& f) {
  const scenes::Scene scene = scenes::load_gltf(f.scene);
  std::unique_ptr<render::EnvironmentLight> environment = render::scene_environment(scene);
  const bool has_environment = environment != nullptr;
  const render::RenderScene render_scene(scene, std::move(environment));
  render::RenderJob job;
  job.width = f.width;
  job.height = f.height;
  job.camera_position = f.camera;
  const render::CameraModel camera = render::job_camera(job, scene, nullptr);
  const render::Effects effects = render::analyse_effects(scene, has_environment);
  fs::create_directories(f.out);

  render::ProbeSettings base;
  render::parse_size(f.grid, "--grid", &base.layout.grid_height, &base.layout.grid_width);
  base.offset = f.offset;
  base.path.max_bounces = f.max_bounces;
  base.progress = false;
  base.seed = f.seed;
  base.photons_per_light = f.photons;
  // The punctual lights' texels are exact and the same in every mode: left out, so that the
  // error is that of the estimated light alone and not diluted by them.
  base.punctual_lights = false;

  std::ostringstream csv;
  csv << "scene,grid,resolution,config,mode,spp,cache_spp,cache_cell_m,probes,seconds,cpu_seconds,extrapolated,"
         "rays,relative_rmse,rmse,reference_noise,reference_spp,subset_probes,cache_cells,cache_fallbacks\n";
  nlohmann::json summary = {{"scene", f.scene}, {"machine", machine_description()}, {"grid", f.grid}, {"rows", nlohmann::json::array()}};
  for (const std::string& res : f.res_list) {
    render::ProbeSettings s = base;
    render::parse_size(res, "--res-list", &s.layout.res_height, &s.layout.res_width);
    s.validate();
    const std::vector<render::ProbeSite> sites = render::place_probes(render_scene, camera, s.layout, s.offset);
    std::vector<int> valid;
    for (size_t p = 0; p < sites.size(); ++p)
      if (sites[p].valid()) valid.push_back(int(p));
    int computed = 0;
    for (const auto& site : sites) computed += site.computed() ? 1 : 0;
    if (valid.empty()) fail("{}: no valid probe in the {} grid", f.scene, f.grid);
    // A random subset of valid probes, the same for every configuration.
    render::Rng pick(0x5eed + f.seed, 3);
    std::vector<int> subset = valid;
    size_t n = std::min(subset.size(), size_t(std::max(f.reference_probes, 1)));
    for (size_t k = 0; k < n; ++k) std::swap(subset[k], subset[k + pick.next_u32() % (subset.size() - k)]);
    subset.resize(n);
    if (!f.probe_indices.empty()) {
      subset.clear();
      for (int p : f.probe_indices) {
        if (p < 0 || size_t(p) >= sites.size() || !sites[size_t(p)].valid())
          fail("--probe-indices: {} is not a valid probe of the {} grid", p, f.grid);
        subset.push_back(p);
      }
      n = subset.size();
    }
    std::sort(subset.begin(), subset.end());

    // Reference: two independent halves, cached on disk by (grid, resolution, spp, seed).
    std::string which = std::to_string(n) + "probes";
    if (!f.probe_indices.empty()) {
      which = "probes";
      for (int p : subset) which += "-" + std::to_string(p);
    }
    const std::string tag = f.grid + "_" + res + "_" + std::to_string(f.reference_spp) + "spp_" + which + "_seed" +
                            std::to_string(f.seed);
    nlohmann::json subset_json = nlohmann::json::array();
    for (int p : subset) {
      const render::ProbeSite& site = sites[size_t(p)];
      subset_json.push_back({{"index", p}, {"i", p / s.layout.grid_width}, {"j", p % s.layout.grid_width},
                             {"origin", {site.origin.x, site.origin.y, site.origin.z}},
                             {"normal", {site.normal.x, site.normal.y, site.normal.z}}});
    }
    summary["subsets"][res] = {{"reference", "reference_" + tag + "_half{0,1}.exr"}, {"probes", subset_json}};
    write_file_atomic(fs::path(f.out) / ("subset_" + tag + ".json"), subset_json.dump(1) + "\n");
    Image halves[2];
    for (int h = 0; h < 2; ++h) {
      const fs::path path = fs::path(f.out) / ("reference_" + tag + "_half" + std::to_string(h) + ".exr");
      if (fs::exists(path)) {
        halves[h] = read_image(path);
        spdlog::info("reusing {}", path.string());
        continue;
      }
      render::ProbeSettings r = s;
      r.mode = render::ProbeMode::kPath;
      r.spp = std::max(f.reference_spp / 2, 1);
      r.seed = f.seed + 1000 + uint64_t(h);
      r.progress = true;
      spdlog::info("reference half {}: {} probes, {}x{} texels, {} spp, path mode", h, n, s.layout.res_height,
                   s.layout.res_width, r.spp);
      const render::ProbeOutput out = render::ProbeRenderer(render_scene, effects, r).render_at(sites, subset);
      halves[h] = strip(out.mosaic, s.layout, subset);
      write_image(path, halves[h]);
    }
    Image reference = halves[0];
    for (size_t k = 0; k < reference.pixels.size(); ++k) reference.pixels[k] = 0.5f * (halves[0].pixels[k] + halves[1].pixels[k]);
    const ImageError split = image_error(halves[0], halves[1]);
    const double reference_noise = split.relative_rmse / 2.0;
    spdlog::info("reference noise (relative RMSE of the mean of two halves): {:.4f}", reference_noise);
    const std::vector<int> classes = classify_texels(render_scene, sites, subset, s.layout, s.glossy_roughness);
    std::vector<std::pair<Config, Image>> measured_strips;

    for (const std::string& text : f.configs) {
      const Config c = parse_config(text, s);
      render::ProbeSettings t = s;
      t.mode = c.mode;
      t.spp = c.spp;
      t.cache.samples_per_cell = c.cache_spp;
      t.cache.direct_distance_cells = c.direct_cells;
      t.spread_threshold = c.spread;
      t.sharing.radius = c.share_radius;
      t.sharing.parallax_texels = c.share_parallax;
      t.cache.cell_size = c.cache_cell;
      t.seed = s.seed + c.seed_offset;
      t.validate();
      const bool extrapolated = c.mode == render::ProbeMode::kPath || f.subset_only;
      const double cpu_start = process_cpu_seconds();
      const render::ProbeOutput out = extrapolated ? render::ProbeRenderer(render_scene, effects, t).render_at(sites, subset)
                                                   : render::ProbeRenderer(render_scene, effects, t).render_at(sites);
      double cpu = process_cpu_seconds() - cpu_start;
      double seconds = out.stats.total_seconds;
      double rays = double(out.stats.counters.rays);
      if (extrapolated) {
        const double scale = double(computed) / double(n);
        seconds *= scale;
        cpu *= scale;
        rays *= scale;
      }
      const Image measured = strip(out.mosaic, s.layout, subset);
      measured_strips.emplace_back(c, measured);
      const ImageError e = image_error(measured, reference);
      std::string name = text;
      std::replace(name.begin(), name.end(), ':', '-');
      write_image(fs::path(f.out) / ("strip_" + f.grid + "_" + res + "_" + name + ".exr"), measured);
      spdlog::info("{} {} {:>14}: {:8.2f} s ({:8.2f} s CPU){}, relative RMSE {:.4f} (reference noise {:.4f})", f.grid, res,
                   text, seconds, cpu, extrapolated ? " extrapolated" : "", e.relative_rmse, reference_noise);
      csv << fs::path(f.scene).stem().string() << ',' << f.grid << ',' << res << ',' << text << ','
          << render::probe_mode_name(c.mode) << ',' << c.spp << ',' << c.cache_spp << ',' << c.cache_cell << ','
          << computed << ',' << seconds << ',' << cpu << ',' << (extrapolated ? 1 : 0) << ',' << rays << ','
          << e.relative_rmse << ',' << e.rmse << ',' << reference_noise << ',' << f.reference_spp << ',' << n << ','
          << out.stats.cache_cells << ',' << out.stats.cache_fallbacks << '\n';
      summary["rows"].push_back({{"resolution", res}, {"config", text}, {"seconds", seconds}, {"cpu_seconds", cpu},
                                 {"extrapolated", extrapolated}, {"relative_rmse", e.relative_rmse},
                                 {"reference_noise", reference_noise}, {"stats", out.stats.to_json()}});
      // Keep what was measured so far, in case the run is interrupted.
      write_file_atomic(fs::path(f.out) / "probes.csv", csv.str());
    }
    // Where the error is, per configuration; paired with a run of the same setting under
    // another seed where the configurations hold one.
    for (size_t a = 0; a < measured_strips.size(); ++a) {
      const Image* other = nullptr;
      for (size_t b = 0; b < measured_strips.size() && !other; ++b)
        if (b != a && same_setting(measured_strips[a].first, measured_strips[b].first)) other = &measured_strips[b].second;
      const nlohmann::json breakdown = error_breakdown(measured_strips[a].second, other, reference, halves, classes,
                                                       subset, sites, s.layout, render_scene);
      log_breakdown(measured_strips[a].first.text, breakdown);
      summary["breakdown"][res][measured_strips[a].first.text] = breakdown;
    }
  }
  const fs::path csv_path = fs::path(f.out) / "probes.csv";
  write_file_atomic(csv_path, csv.str());
  write_file_atomic(fs::path(f.out) / "probes.json", summary.dump(2) + "\n");
  write_file_atomic(fs::path(f.out) / "machine.txt", machine_description() + "\n");
  const fs::path script = fs::path(PHYIR_SOURCE_ROOT) / "scripts" / "plot_probes.py";
  const std::string cmd = "/usr/bin/python3 '" + script.string() + "' '" + csv_path.string() + "' '" +
                          (fs::path(f.out) / "probes.png").string() + "'";
  if (std::system(cmd.c_str()) != 0) spdlog::warn("plot not written: {} failed (python3-matplotlib missing?)", script.string());
  spdlog::info("wrote {}", csv_path.string());
}

}  // namespace

void add_bench_probes_command(CLI::App& bench) {
  auto f = std::make_shared<BenchProbeFlags>();
  auto* cmd = bench.add_subcommand("probes", "light probes: relative RMSE against a converged reference versus seconds, per mode and setting");
  cmd->add_option("scene", f->scene, "glTF scene to measure on (or --suite)")->check(CLI::ExistingFile);
  cmd->add_option("--suite", f->suite, "suite.json of 'phyir bench suite': measure on every scene, into OUT/<name>/")
      ->check(CLI::ExistingFile);
  cmd->add_option("--out", f->out, "folder for probes.csv, probes.png, probes.json and the cached references")->capture_default_str();
  cmd->add_option("--grid", f->grid, "probe grid HxW the times are measured on")->capture_default_str();
  cmd->add_option("--res-list", f->res_list, "probe resolutions hxw")->delimiter(',')->capture_default_str();
  cmd->add_option("--configs", f->configs,
                  std::string(kConfigSyntax) + " settings to measure (SEED: added to --seed, for repeated runs; DIRECT_CELLS, SPREAD, SHARE_RADIUS, SHARE_PARALLAX: as --probe-cache-direct-cells, --probe-spread-threshold, --probe-share-radius, --probe-share-parallax)")->delimiter(',')->capture_default_str();
  cmd->add_option("--reference-spp", f->reference_spp, "spp of the converged path-mode reference")->capture_default_str();
  cmd->add_option("--reference-probes", f->reference_probes, "how many random valid probes the error is measured on")->capture_default_str();
  cmd->add_option("--probe-indices", f->probe_indices, "measure on these probe indices (i * grid width + j) instead of a random subset")->delimiter(',');
  cmd->add_flag("--subset-only", f->subset_only, "cache mode renders only the measured probes too (a study aid: its cache then sees only them; times extrapolated)");
  cmd->add_option("--threads", f->threads, "worker threads (0 = all cores)")->capture_default_str();
  cmd->add_option("--max-bounces", f->max_bounces, "path length")->capture_default_str();
  cmd->add_option("--seed", f->seed, "random seed")->capture_default_str();
  cmd->add_option("--offset", f->offset, "probe origin offset, metres")->capture_default_str();
  cmd->add_option("--probe-photons", f->photons, "cache mode: photons per point or spot light and per square metre of the sun's beam, as phyir render's (0: none)")
      ->capture_default_str();
  cmd->callback([f] {
    const int threads = f->threads > 0 ? f->threads : tbb::info::default_concurrency();
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    run_scene_or_suite(*f, &run_bench_probes, "probes.json", "phyir bench probes");
  });
}

}  // namespace phyir::cli
