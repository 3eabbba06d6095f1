#include "phyir/dataset/generate.h"

#include <tbb/global_control.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_pipeline.h>
#include <tbb/task_arena.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <map>
#include <mutex>
#include <set>

#include <fmt/format.h>

#include "phyir/core/atomic_file.h"
#include "phyir/core/error.h"
#include "phyir/core/image_io.h"
#include "phyir/core/log.h"
#include "phyir/core/progress.h"
#include "phyir/dataset/checksum.h"
#include "phyir/dataset/input_image.h"
#include "phyir/dataset/layout.h"
#include "phyir/dataset/manifest.h"
#include "phyir/dataset/split.h"
#include "phyir/dataset/verify.h"
#include "phyir/dataset/viewpoints.h"
#include "phyir/render/render_job.h"
#include "phyir/scenes/gltf_loader.h"

namespace phyir::dataset {

namespace fs = std::filesystem;
using nlohmann::json;
using Clock = std::chrono::steady_clock;

namespace {

double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

bool ends_with(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

bool is_timing_key(const std::string& key) {
  return key == "timings" || key == "threads" || key == "seconds" || ends_with(key, "_seconds") ||
         ends_with(key, "per_second");
}

void move_timing(json& value, json& timing) {
  if (!value.is_object()) return;
  std::vector<std::string> keys;
  for (auto it = value.begin(); it != value.end(); ++it) keys.push_back(it.key());
  for (const std::string& key : keys) {
    if (is_timing_key(key)) {
      timing[key] = std::move(value[key]);
      value.erase(key);
    } else if (value[key].is_object()) {
      json nested = json::object();
      move_timing(value[key], nested);
      if (!nested.empty()) timing[key] = std::move(nested);
    }
  }
}

// One scene of the shard.
struct SceneWork {
  SceneFile file;
  std::string split;
  json record;                       // scene_record()
  std::vector<Viewpoint> viewpoints;  // planned only when a view of it is rendered
  std::string plan_error;
};

struct ViewTask {
  size_t scene = 0;  // into the shard's SceneWork list
  int index = 0;
  std::string id;
  fs::path folder;  // relative to the output folder
  uint64_t seed = 0;
};

struct Context {
  const GenerateOptions* options = nullptr;
  json settings_json;
  std::string settings_sha256;
  int threads = 1;
};

// What the folder of a finished view holds, checked cheaply (record, scene, sizes).
enum class Existing { Missing, Complete, Damaged, OtherScene };

Existing check_existing(const Context& ctx, const ViewTask& task, const SceneWork& scene, json* record,
                        std::string* why) {
  const fs::path folder = ctx.options->out_dir / task.folder;
  std::error_code ec;
  if (!fs::exists(folder, ec)) return Existing::Missing;
  try {
    *record = json::parse(read_file(folder / kViewRecordFile));
  } catch (const std::exception& e) {
    *why = fmt::format("its {} is unreadable ({})", kViewRecordFile, e.what());
    return Existing::Damaged;
  }
  const json& r = *record;
  if (r.value("id", "") != task.id || r.value("seed", json()) != json(task.seed) ||
      r.value("settings_sha256", "") != ctx.settings_sha256) {
    *why = "its record names another view, seed or settings";
    return Existing::Damaged;
  }
  if (!r.contains("scene") || r["scene"].value("content_sha256", "") != scene.record["content_sha256"]) {
    *why = fmt::format("it was rendered from other contents of {} (content_sha256 {}, now {})", scene.file.file,
                       r.contains("scene") ? r["scene"].value("content_sha256", "?") : "?",
                       scene.record["content_sha256"].get<std::string>());
    return Existing::OtherScene;
  }
  for (const json& f : r.value("files", json::array())) {
    const fs::path path = folder / f.value("path", "");
    const auto size = fs::file_size(path, ec);
    if (ec || json(size) != f.value("size", json())) {
      *why = fmt::format("{} is missing or has the wrong size", path.filename().string());
      return Existing::Damaged;
    }
  }
  return Existing::Complete;
}

// Renders, checks and commits one view folder; returns its record.
json render_view_folder(const Context& ctx, const ViewTask& task, const SceneWork& scene) {
  const GenerateOptions& o = *ctx.options;
  const DatasetSettings& s = o.settings;
  const auto start = Clock::now();
  const Viewpoint& viewpoint = scene.viewpoints.at(size_t(task.index));
  const fs::path final_folder = o.out_dir / task.folder;
  const fs::path tmp = final_folder.parent_path() / (kTemporaryPrefix + final_folder.filename().string());
  std::error_code ec;
  fs::remove_all(tmp, ec);
  fs::create_directories(tmp, ec);
  if (ec) fail("{}: cannot create: {}", tmp.string(), ec.message());

  render::RenderJob job;
  job.scene_path = o.scenes_dir / scene.file.file;
  job.out_dir = tmp;
  job.projection = render::Projection::Equirectangular;
  job.width = s.width;
  job.height = s.height;
  job.camera_position = viewpoint.position;
  job.settings.spp = s.spp;
  job.settings.seed = task.seed;
  job.settings.path.max_bounces = s.max_bounces;
  job.settings.aovs = true;
  job.settings.progress = false;
  job.threads = ctx.threads;
  job.exposure = s.preview_exposure;
  job.view = "Standard";
  job.probes = s.probes;
  job.probe = s.probe;
  render::RenderReport report = render::run_render_job(job);

  // The network's input.
  const Image color = read_image(tmp / "color.exr");
  const InputExposure exposure = choose_input_exposure(color, s.input, task.seed);
  write_input_image(tmp / kInputFile, color, exposure, s.input);

  // render.json without wall-clock values (they go to timing.json) and with the scene path
  // relative to the scenes folder, so the folder's bytes depend only on the inputs.
  report.scene.path = scene.file.file;
  json render_record = report.to_json();
  json timing = json::object();
  move_timing(render_record, timing);
  write_file_atomic(tmp / kRenderRecordFile, render_record.dump(2) + "\n");

  // Every file, re-read: decodable, finite, checksummed.
  std::vector<std::string> names = report.files;
  names.push_back(kInputFile);
  names.push_back(kRenderRecordFile);
  std::sort(names.begin(), names.end());
  names.erase(std::unique(names.begin(), names.end()), names.end());
  json files = json::array();
  for (const std::string& name : names) {
    FileCheck check = inspect_file(tmp, name);
    if (!check.problem.empty()) fail("{}: {}", (tmp / name).string(), check.problem);
    files.push_back(std::move(check.record));
  }
  for (const fs::directory_entry& entry : fs::directory_iterator(tmp)) {
    const std::string name = entry.path().filename().string();
    if (!std::binary_search(names.begin(), names.end(), name))
      fail("{}: unexpected file {} after rendering", tmp.string(), name);
  }

  // The view's record holds no wall-clock values either.
  json counters = report.stats.to_json();
  json counter_seconds = json::object();
  move_timing(counters, counter_seconds);
  json render_stats = {{"effects", report.effects.to_json()},
                       {"counters", counters},
                       {"scene_triangles", report.scene.triangles}};
  if (report.probes) {
    const render::ProbeStats& p = report.probes->stats;
    render_stats["probes"] = {{"counts", p.counts_json()},
                              {"rays", p.rays()},
                              {"paths", p.counters.paths},
                              {"supersampled_texels", p.supersampled_texels},
                              {"cache", p.cache_json()},
                              {"nonfinite_samples_caught", p.counters.nonfinite_samples}};
  }
  const json record = tidy_floats({{"id", task.id},
                       {"scene",
                        {{"name", scene.file.name},
                         {"file", scene.file.file},
                         {"sha256", scene.record["sha256"]},
                         {"content_sha256", scene.record["content_sha256"]}}},
                       {"index", task.index},
                       {"split", scene.split},
                       {"dir", task.folder.generic_string()},
                       {"seed", task.seed},
                       {"viewpoint", viewpoint.to_json()},
                       {"input", exposure.to_json(s.input)},
                       {"render", render_stats},
                       {"settings_sha256", ctx.settings_sha256},
                       {"files", files}});
  timing["view_seconds"] = seconds_since(start);
  write_file_atomic(tmp / kTimingFile, timing.dump(2) + "\n");
  write_file_atomic(tmp / kViewRecordFile, record.dump(2) + "\n");
  sync_folder(tmp);

  // Commit: one rename makes the view complete.
  fs::remove_all(final_folder, ec);
  fs::rename(tmp, final_folder, ec);
  if (ec) fail("{}: cannot move the finished view into place: {}", final_folder.string(), ec.message());
  sync_folder(final_folder.parent_path());
  return record;
}

void write_settings_file(const fs::path& out, const json& settings_json) {
  const fs::path path = out / kSettingsFile;
  const json wanted = {{"format", kManifestFormat},
                       {"generator", std::string("phyir ") + PHYIR_VERSION},
                       {"settings", settings_json}};
  std::error_code ec;
  if (fs::exists(path, ec)) {
    const json existing = json::parse(read_file(path), nullptr, false);
    if (existing.is_discarded())
      fail("{}: not valid JSON; delete it (and the views it describes) or use another --out", path.string());
    const std::string difference = describe_difference(existing, wanted, "settings.json");
    if (!difference.empty())
      fail("{} holds a dataset made with other settings ({} here vs this command); use another --out, or delete "
           "the folder to start over",
           out.string(), difference);
    return;
  }
  write_file_atomic(path, wanted.dump(2) + "\n");
}

std::string format_duration(double s) {
  if (!(s >= 0) || s > 1e8) return "?";
  if (s < 60) return fmt::format("{:.0f}s", s);
  if (s < 3600) return fmt::format("{}m{:02d}s", int(s) / 60, int(s) % 60);
  return fmt::format("{}h{:02d}m", int(s) / 3600, (int(s) / 60) % 60);
}

}  // namespace

json split_timing(json report, json* timing) {
  json moved = json::object();
  move_timing(report, moved);
  if (timing) *timing = std::move(moved);
  return report;
}

GenerateSummary generate_dataset(const GenerateOptions& o) {
  const auto run_start = Clock::now();
  const DatasetSettings& s = o.settings;
  s.validate();
  if (o.threads < 0) fail("--threads {} must be >= 0 (0 = all cores)", o.threads);
  if (o.views_in_flight < 0) fail("--views-in-flight {} must be >= 0", o.views_in_flight);
  const std::vector<SceneFile> scene_files = list_scenes(o.scenes_dir);
  const int K = s.views_per_scene;

  Context ctx;
  ctx.options = &o;
  ctx.settings_json = s.to_json();
  ctx.settings_sha256 = sha256_hex(ctx.settings_json.dump());
  ctx.threads = o.threads > 0 ? o.threads : tbb::info::default_concurrency();
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(ctx.threads));

  std::error_code ec;
  fs::create_directories(o.out_dir / kViewsFolder, ec);
  if (ec) fail("--out {}: cannot create: {}", o.out_dir.string(), ec.message());
  const FolderLock lock(o.out_dir, "generate");
  if (const size_t removed = remove_temporaries(o.out_dir))
    spdlog::info("removed {} interrupted write(s) from an earlier run", removed);
  write_settings_file(o.out_dir, ctx.settings_json);

  // This shard's views and scenes.
  const size_t total = scene_files.size() * size_t(K);
  const auto [begin, end] = shard_range(total, o.shard);
  std::vector<SceneWork> scenes;
  std::vector<ViewTask> tasks;
  std::map<size_t, size_t> scene_slot;  // index in scene_files -> index in scenes
  for (size_t g = begin; g < end; ++g) {
    const size_t si = g / size_t(K);
    const int k = int(g % size_t(K));
    if (!scene_slot.count(si)) {
      scene_slot[si] = scenes.size();
      SceneWork w;
      w.file = scene_files[si];
      w.split = split_name(split_for_scene(w.file.name, s.seed, s.split));
      scenes.push_back(std::move(w));
    }
    const std::string& name = scene_files[si].name;
    tasks.push_back({scene_slot[si], k, view_id(name, k, K), view_folder(name, k, K), view_seed(s.seed, name, k)});
  }
  tbb::parallel_for(size_t(0), scenes.size(), [&](size_t i) {
    scenes[i].record = scene_record(o.scenes_dir, scenes[i].file, scenes[i].split, K);
  });

  // What is already there.
  std::vector<json> records(tasks.size());
  std::vector<size_t> pending;
  std::vector<std::string> changed;
  for (size_t t = 0; t < tasks.size(); ++t) {
    std::string why;
    switch (check_existing(ctx, tasks[t], scenes[tasks[t].scene], &records[t], &why)) {
      case Existing::Complete: break;
      case Existing::Missing: pending.push_back(t); break;
      case Existing::Damaged: {
        spdlog::warn("{}: rendering it again: {}", tasks[t].id, why);
        const fs::path folder = o.out_dir / tasks[t].folder;
        const fs::path doomed = folder.parent_path() / (kTemporaryPrefix + folder.filename().string());
        fs::remove_all(doomed, ec);
        fs::rename(folder, doomed, ec);
        fs::remove_all(doomed, ec);
        pending.push_back(t);
        break;
      }
      case Existing::OtherScene: changed.push_back(tasks[t].id + ": " + why); break;
    }
  }
  if (!changed.empty())
    fail("{}: {} existing view(s) do not match the scenes now in {}, e.g. {}; delete those views (or the folder) or "
         "use another --out",
         o.out_dir.string(), changed.size(), o.scenes_dir.string(), changed.front());

  GenerateSummary summary;
  summary.views = tasks.size();
  summary.kept = tasks.size() - pending.size();
  if (summary.kept > 0)
    spdlog::info("{}: {} of {} views of shard {} already complete; rendering the other {}", o.out_dir.string(),
                 summary.kept, tasks.size(), shard_name(o.shard), pending.size());
  if (!pending.empty()) fs::remove(o.out_dir / kManifestFile, ec);  // the dataset is not complete

  // Viewpoints of the scenes that still have views to render.
  std::set<size_t> to_plan;
  for (size_t t : pending) to_plan.insert(tasks[t].scene);
  const std::vector<size_t> plan_list(to_plan.begin(), to_plan.end());
  tbb::parallel_for(size_t(0), plan_list.size(), [&](size_t i) {
    SceneWork& w = scenes[plan_list[i]];
    try {
      const scenes::Scene scene = scenes::load_gltf(o.scenes_dir / w.file.file);
      w.viewpoints = plan_viewpoints(scene, w.file.name, K, s.seed, s.viewpoints);
    } catch (const std::exception& e) {
      w.plan_error = e.what();
    }
  });

  // Render.
  std::mutex mutex;
  std::vector<std::string> failures;
  std::atomic<size_t> done{0};
  const auto render_start = Clock::now();
  {
    // On a terminal one live line (views done, views/hour, time left); in logs (Slurm) a line
    // per finished view says the same, since a log line every few seconds would be noise.
    const bool live = o.progress && ::isatty(STDERR_FILENO);
    Progress progress("dataset", pending.size(), "views", live);
    progress.set_rate(ProgressRate::PerHour);
    const size_t in_flight = size_t(o.views_in_flight > 0 ? o.views_in_flight : ctx.threads);
    size_t next = 0;
    tbb::parallel_pipeline(
        in_flight,
        tbb::make_filter<void, size_t>(tbb::filter_mode::serial_in_order,
                                       [&](tbb::flow_control& fc) -> size_t {
                                         if (next >= pending.size()) {
                                           fc.stop();
                                           return 0;
                                         }
                                         return pending[next++];
                                       }) &
            tbb::make_filter<size_t, void>(tbb::filter_mode::parallel, [&](size_t t) {
              const ViewTask& task = tasks[t];
              const SceneWork& scene = scenes[task.scene];
              const auto view_start = Clock::now();
              try {
                if (!scene.plan_error.empty()) fail("{}", scene.plan_error);
                // Isolated: a thread waiting inside this render must not pick up another view.
                tbb::this_task_arena::isolate([&] { records[t] = render_view_folder(ctx, task, scene); });
              } catch (const std::exception& e) {
                std::lock_guard<std::mutex> lock(mutex);
                failures.push_back(task.id + ": " + e.what());
                spdlog::error("{}: failed: {}", task.id, e.what());
                return;
              }
              const size_t n = ++done;
              progress.advance();
              const double elapsed = seconds_since(render_start);
              const double per_hour = elapsed > 0 ? 3600.0 * double(n) / elapsed : 0.0;
              spdlog::log(live ? spdlog::level::debug : spdlog::level::info,
                          "dataset: {} done in {:.1f} s; {}/{} views, {:.0f} views/hour, {} left", task.id,
                          seconds_since(view_start), n, pending.size(), per_hour,
                          format_duration(per_hour > 0 ? 3600.0 * double(pending.size() - n) / per_hour : -1.0));
            }));
  }
  summary.rendered = done;
  const double render_seconds = seconds_since(render_start);
  summary.views_per_hour = render_seconds > 0 ? 3600.0 * double(summary.rendered) / render_seconds : 0.0;
  if (!failures.empty()) {
    std::sort(failures.begin(), failures.end());
    std::string list;
    for (size_t i = 0; i < failures.size() && i < 10; ++i) list += "\n  " + failures[i];
    fail("{} of {} views failed (the {} complete ones are kept; run the same command again to retry):{}{}",
         failures.size(), tasks.size(), tasks.size() - failures.size(), list,
         failures.size() > 10 ? fmt::format("\n  ... and {} more", failures.size() - 10) : std::string());
  }

  // The manifest, from the views' own records.
  Manifest manifest;
  manifest.settings = ctx.settings_json;
  manifest.scenes_dir = o.scenes_dir.generic_string();
  manifest.shard = o.shard;
  for (const SceneFile& f : scene_files) manifest.scene_names.push_back(f.name);
  for (const SceneWork& w : scenes) manifest.scenes.push_back(w.record);
  manifest.views = records;
  write_manifest(o.out_dir, manifest);
  summary.seconds = seconds_since(run_start);
  spdlog::info("dataset {}: {} views of shard {} ({} rendered, {} kept) in {}{}; wrote {}", o.out_dir.string(),
               summary.views, shard_name(o.shard), summary.rendered, summary.kept, format_duration(summary.seconds),
               summary.rendered > 0 ? fmt::format(", {:.0f} views/hour", summary.views_per_hour) : std::string(),
               kManifestFile);
  return summary;
}

}  // namespace phyir::dataset
