#include "phyir/dataset/generate.h"

#include <tbb/global_control.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_pipeline.h>
#include <tbb/task_arena.h>
#include <unistd.h>

#include <atomic>
#include <map>
#include <mutex>
#include <set>

#include <fmt/format.h>

#include "phyir/core/atomic_file.h"
#include "phyir/core/error.h"
#include "phyir/core/image_io.h"
#include "phyir/core/log.h"
#include "phyir/core/progress.h"
#include "phyir/core/setting_error.h"
#include "phyir/core/stopwatch.h"
#include "phyir/dataset/checksum.h"
#include "phyir/dataset/input_image.h"
#include "phyir/dataset/layout.h"
#include "phyir/dataset/manifest.h"
#include "phyir/dataset/split.h"
#include "phyir/dataset/verify.h"
#include "phyir/dataset/viewpoints.h"
#include "phyir/render/render_job.h"
#include "phyir/scenes/gltf_loader.h"
#include "phyir/view/view_files.h"
#include "phyir/view/view_record.h"

namespace phyir::dataset {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

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
    *record = view::read_view_json(folder);
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

// The render job of a view: the dataset's settings at the view's viewpoint and seed.
render::RenderJob view_render_job(const Context& ctx, const ViewTask& task, const SceneWork& scene,
                                  const fs::path& out_dir) {
  const GenerateOptions& o = *ctx.options;
  const DatasetSettings& s = o.settings;
  render::RenderJob job;
  job.scene_path = o.scenes_dir / scene.file.file;
  job.out_dir = out_dir;
  job.projection = render::Projection::Equirectangular;
  job.width = s.width;
  job.height = s.height;
  job.camera_position = scene.viewpoints.at(size_t(task.index)).position;
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
  return job;
}

// render.json without wall-clock values (they go to `timing`) and with the scene path
// relative to the scenes folder, so the folder's bytes depend only on the inputs.
void write_render_record(render::RenderReport report, const SceneWork& scene, const fs::path& tmp, json& timing) {
  report.scene.path = scene.file.file;
  json render_record = report.to_json();
  move_timing(render_record, timing);
  write_file_atomic(tmp / kRenderRecordFile, render_record.dump(2) + "\n");
}

// Every file the view should hold, re-read: decodable, finite, checksummed; nothing else there.
json check_view_files(const fs::path& tmp, std::vector<std::string> names) {
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
  return files;
}

// The render statistics of the view's record: no wall-clock values either.
json render_statistics(const render::RenderReport& report) {
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
  return render_stats;
}

// view.json (view/view_record.h): the view's manifest entry.
json view_record(const Context& ctx, const ViewTask& task, const SceneWork& scene, const InputExposure& exposure,
                 json render_stats, json files) {
  return tidy_floats({{"id", task.id},
                      {"scene",
                       {{"name", scene.file.name},
                        {"file", scene.file.file},
                        {"sha256", scene.record["sha256"]},
                        {"content_sha256", scene.record["content_sha256"]}}},
                      {"index", task.index},
                      {"split", scene.split},
                      {"dir", task.folder.generic_string()},
                      {"seed", task.seed},
                      {"viewpoint", scene.viewpoints.at(size_t(task.index)).to_json()},
                      {"input", exposure.to_json()},
                      {"render", std::move(render_stats)},
                      {"settings_sha256", ctx.settings_sha256},
                      {"files", std::move(files)}});
}

// One rename makes the view complete.
void commit_view_folder(const fs::path& tmp, const fs::path& final_folder) {
  std::error_code ec;
  fs::remove_all(final_folder, ec);
  fs::rename(tmp, final_folder, ec);
  if (ec) fail("{}: cannot move the finished view into place: {}", final_folder.string(), ec.message());
  sync_folder(final_folder.parent_path());
}

// Renders, checks and commits one view folder; returns its record.
json render_view_folder(const Context& ctx, const ViewTask& task, const SceneWork& scene) {
  const Stopwatch watch;
  const fs::path final_folder = ctx.options->out_dir / task.folder;
  const fs::path tmp = final_folder.parent_path() / (kTemporaryPrefix + final_folder.filename().string());
  std::error_code ec;
  fs::remove_all(tmp, ec);
  fs::create_directories(tmp, ec);
  if (ec) fail("{}: cannot create: {}", tmp.string(), ec.message());
  const render::RenderReport report = render::run_render_job(view_render_job(ctx, task, scene, tmp));

  // The network's input.
  const InputSettings& input = ctx.options->settings.input;
  const Image color = read_image(tmp / view::kColorFile);
  const InputExposure exposure = choose_input_exposure(color, input, task.seed);
  write_input_image(tmp / kInputFile, color, exposure, input);

  json timing = json::object();
  write_render_record(report, scene, tmp, timing);
  json files = check_view_files(tmp, report.files);
  const json record = view_record(ctx, task, scene, exposure, render_statistics(report), std::move(files));
  timing["view_seconds"] = watch.seconds();
  write_file_atomic(tmp / kTimingFile, timing.dump(2) + "\n");
  view::write_view_record(tmp, record);
  sync_folder(tmp);
  commit_view_folder(tmp, final_folder);
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
      fail("{}: not valid JSON; delete it (and the views it describes) or use another output folder", path.string());
    const std::string difference = describe_difference(existing, wanted, kSettingsFile);
    if (!difference.empty())
      fail("{} holds a dataset made with other settings ({} here vs this command); use another output folder, or delete "
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

namespace {

// The views of this shard and the scenes they belong to.
struct ShardWork {
  std::vector<SceneWork> scenes;
  std::vector<ViewTask> tasks;
};

ShardWork plan_shard(const GenerateOptions& o, const std::vector<SceneFile>& scene_files) {
  const DatasetSettings& s = o.settings;
  const int K = s.views_per_scene;
  const size_t total = scene_files.size() * size_t(K);
  const auto [begin, end] = shard_range(total, o.shard);
  ShardWork work;
  std::map<size_t, size_t> scene_slot;  // index in scene_files -> index in work.scenes
  for (size_t g = begin; g < end; ++g) {
    const size_t si = g / size_t(K);
    const int k = int(g % size_t(K));
    if (!scene_slot.count(si)) {
      scene_slot[si] = work.scenes.size();
      SceneWork w;
      w.file = scene_files[si];
      w.split = split_name(split_for_scene(w.file.name, s.seed, s.split));
      work.scenes.push_back(std::move(w));
    }
    const std::string& name = scene_files[si].name;
    work.tasks.push_back({scene_slot[si], k, view_id(name, k, K), view_folder(name, k, K), view_seed(s.seed, name, k)});
  }
  tbb::parallel_for(size_t(0), work.scenes.size(), [&](size_t i) {
    work.scenes[i].record = scene_record(o.scenes_dir, work.scenes[i].file, work.scenes[i].split, K);
  });
  return work;
}

// What is already there: the complete views' records go into `records`; returns the tasks
// still to render. Damaged views are moved aside and deleted; views of changed scenes fail.
std::vector<size_t> triage_existing(const Context& ctx, const ShardWork& work, std::vector<json>& records) {
  const GenerateOptions& o = *ctx.options;
  std::vector<size_t> pending;
  std::vector<std::string> changed;
  std::error_code ec;
  for (size_t t = 0; t < work.tasks.size(); ++t) {
    const ViewTask& task = work.tasks[t];
    std::string why;
    switch (check_existing(ctx, task, work.scenes[task.scene], &records[t], &why)) {
      case Existing::Complete: break;
      case Existing::Missing: pending.push_back(t); break;
      case Existing::Damaged: {
        spdlog::warn("{}: rendering it again: {}", task.id, why);
        const fs::path folder = o.out_dir / task.folder;
        const fs::path doomed = folder.parent_path() / (kTemporaryPrefix + folder.filename().string());
        fs::remove_all(doomed, ec);
        fs::rename(folder, doomed, ec);
        fs::remove_all(doomed, ec);
        pending.push_back(t);
        break;
      }
      case Existing::OtherScene: changed.push_back(task.id + ": " + why); break;
    }
  }
  if (!changed.empty())
    fail("{}: {} existing view(s) do not match the scenes now in {}, e.g. {}; delete those views (or the folder) or "
         "use another output folder",
         o.out_dir.string(), changed.size(), o.scenes_dir.string(), changed.front());
  return pending;
}

// Viewpoints of the scenes that still have views to render (a scene that cannot be planned
// fails its views, not the run).
void plan_pending_viewpoints(const GenerateOptions& o, ShardWork& work, const std::vector<size_t>& pending) {
  std::set<size_t> to_plan;
  for (size_t t : pending) to_plan.insert(work.tasks[t].scene);
  const std::vector<size_t> plan_list(to_plan.begin(), to_plan.end());
  tbb::parallel_for(size_t(0), plan_list.size(), [&](size_t i) {
    SceneWork& w = work.scenes[plan_list[i]];
    try {
      const scenes::Scene scene = scenes::load_gltf(o.scenes_dir / w.file.file);
      w.viewpoints = plan_viewpoints(scene, w.file.name, o.settings.views_per_scene, o.settings.seed,
                                     o.settings.viewpoints);
    } catch (const std::exception& e) {
      w.plan_error = e.what();
    }
  });
}

// Renders the pending views, `in_flight` at a time; a view that fails is listed, not fatal.
class PendingRenders {
 public:
  PendingRenders(const Context& ctx, const ShardWork& work, const std::vector<size_t>& pending,
                 std::vector<json>& records)
      : ctx_(ctx), work_(work), pending_(pending), records_(records) {}

  // Returns the number rendered; throws listing the failures after every view was tried.
  size_t run() {
    // On a terminal one live line (views done, views/hour, time left); in logs (Slurm) a line
    // per finished view says the same, since a log line every few seconds would be noise.
    live_ = ctx_.options->progress && ::isatty(STDERR_FILENO);
    Progress progress("dataset", pending_.size(), "views", live_);
    progress.set_rate(ProgressRate::PerHour);
    progress_ = &progress;
    watch_ = Stopwatch();
    const int views_in_flight = ctx_.options->views_in_flight;
    const size_t in_flight = size_t(views_in_flight > 0 ? views_in_flight : ctx_.threads);
    size_t next = 0;
    tbb::parallel_pipeline(in_flight,
                           tbb::make_filter<void, size_t>(tbb::filter_mode::serial_in_order,
                                                          [&](tbb::flow_control& fc) -> size_t {
                                                            if (next >= pending_.size()) {
                                                              fc.stop();
                                                              return 0;
                                                            }
                                                            return pending_[next++];
                                                          }) &
                               tbb::make_filter<size_t, void>(tbb::filter_mode::parallel,
                                                              [&](size_t t) { render_one(t); }));
    progress_ = nullptr;
    seconds_ = watch_.seconds();
    report_failures();
    return done_;
  }

  double seconds() const { return seconds_; }

 private:
  void render_one(size_t t) {
    const ViewTask& task = work_.tasks[t];
    const SceneWork& scene = work_.scenes[task.scene];
    const Stopwatch view_watch;
    try {
      if (!scene.plan_error.empty()) fail("{}", scene.plan_error);
      // Isolated: a thread waiting inside this render must not pick up another view.
      tbb::this_task_arena::isolate([&] { records_[t] = render_view_folder(ctx_, task, scene); });
    } catch (const std::exception& e) {
      std::lock_guard<std::mutex> lock(mutex_);
      failures_.push_back(task.id + ": " + e.what());
      spdlog::error("{}: failed: {}", task.id, e.what());
      return;
    }
    const size_t n = ++done_;
    progress_->advance();
    const double elapsed = watch_.seconds();
    const double per_hour = elapsed > 0 ? 3600.0 * double(n) / elapsed : 0.0;
    spdlog::log(live_ ? spdlog::level::debug : spdlog::level::info,
                "dataset: {} done in {:.1f} s; {}/{} views, {:.0f} views/hour, {} left", task.id,
                view_watch.seconds(), n, pending_.size(), per_hour,
                format_duration(per_hour > 0 ? 3600.0 * double(pending_.size() - n) / per_hour : -1.0));
  }

  void report_failures() {
    if (failures_.empty()) return;
    std::sort(failures_.begin(), failures_.end());
    std::string list;
    for (size_t i = 0; i < failures_.size() && i < 10; ++i) list += "\n  " + failures_[i];
    const size_t total = work_.tasks.size();
    fail("{} of {} views failed (the {} complete ones are kept; run the same command again to retry):{}{}",
         failures_.size(), total, total - failures_.size(), list,
         failures_.size() > 10 ? fmt::format("\n  ... and {} more", failures_.size() - 10) : std::string());
  }

  const Context& ctx_;
  const ShardWork& work_;
  const std::vector<size_t>& pending_;
  std::vector<json>& records_;
  std::mutex mutex_;
  std::vector<std::string> failures_;
  std::atomic<size_t> done_{0};
  Stopwatch watch_;
  double seconds_ = 0.0;
  bool live_ = false;
  Progress* progress_ = nullptr;
};

// The run's context; the output folder created, locked, cleaned and its settings recorded.
Context open_output(const GenerateOptions& o) {
  Context ctx;
  ctx.options = &o;
  ctx.settings_json = o.settings.to_json();
  ctx.settings_sha256 = sha256_hex(ctx.settings_json.dump());
  ctx.threads = o.threads > 0 ? o.threads : tbb::info::default_concurrency();
  return ctx;
}

void prepare_output_folder(const Context& ctx) {
  const GenerateOptions& o = *ctx.options;
  std::error_code ec;
  fs::create_directories(o.out_dir / kViewsFolder, ec);
  if (ec) fail_setting("out_dir", "{}: cannot create: {}", o.out_dir.string(), ec.message());
}

// The manifest, from the views' own records.
void write_run_manifest(const Context& ctx, const std::vector<SceneFile>& scene_files, const ShardWork& work,
                        std::vector<json> records) {
  const GenerateOptions& o = *ctx.options;
  Manifest manifest;
  manifest.settings = ctx.settings_json;
  manifest.scenes_dir = o.scenes_dir.generic_string();
  manifest.shard = o.shard;
  for (const SceneFile& f : scene_files) manifest.scene_names.push_back(f.name);
  for (const SceneWork& w : work.scenes) manifest.scenes.push_back(w.record);
  manifest.views = std::move(records);
  write_manifest(o.out_dir, manifest);
}

}  // namespace

GenerateSummary generate_dataset(const GenerateOptions& o) {
  const Stopwatch run_watch;
  o.settings.validate();
  if (o.threads < 0) fail_setting("threads", "{} must be >= 0 (0 = all cores)", o.threads);
  if (o.views_in_flight < 0) fail_setting("views_in_flight", "{} must be >= 0", o.views_in_flight);
  const std::vector<SceneFile> scene_files = list_scenes(o.scenes_dir);
  const Context ctx = open_output(o);
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(ctx.threads));
  prepare_output_folder(ctx);
  const FolderLock lock(o.out_dir, "generate");
  if (const size_t removed = remove_temporaries(o.out_dir))
    spdlog::info("removed {} interrupted write(s) from an earlier run", removed);
  write_settings_file(o.out_dir, ctx.settings_json);

  ShardWork work = plan_shard(o, scene_files);
  std::vector<json> records(work.tasks.size());
  const std::vector<size_t> pending = triage_existing(ctx, work, records);
  GenerateSummary summary;
  summary.views = work.tasks.size();
  summary.kept = work.tasks.size() - pending.size();
  if (summary.kept > 0)
    spdlog::info("{}: {} of {} views of shard {} already complete; rendering the other {}", o.out_dir.string(),
                 summary.kept, work.tasks.size(), shard_name(o.shard), pending.size());
  std::error_code ec;
  if (!pending.empty()) fs::remove(o.out_dir / kManifestFile, ec);  // the dataset is not complete
  plan_pending_viewpoints(o, work, pending);

  PendingRenders renders(ctx, work, pending, records);
  summary.rendered = renders.run();
  summary.views_per_hour = renders.seconds() > 0 ? 3600.0 * double(summary.rendered) / renders.seconds() : 0.0;
  write_run_manifest(ctx, scene_files, work, std::move(records));
  summary.seconds = run_watch.seconds();
  spdlog::info("dataset {}: {} views of shard {} ({} rendered, {} kept) in {}{}; wrote {}", o.out_dir.string(),
               summary.views, shard_name(o.shard), summary.rendered, summary.kept, format_duration(summary.seconds),
               summary.rendered > 0 ? fmt::format(", {:.0f} views/hour", summary.views_per_hour) : std::string(),
               kManifestFile);
  return summary;
}

}  // namespace phyir::dataset
