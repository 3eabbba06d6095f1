#pragma once
// `phyir dataset generate`: every view of every scene of a folder, rendered with
// run_render_job into its own folder with the network's input, checked, checksummed and
// renamed into place; manifest.json last.
//
// Crash safety and resume: a view is rendered into views/<scene>/.tmp-<v>, each file there
// written atomically, every file re-read (images decoded by OpenImageIO, values checked
// finite) and checksummed, view.json (the view's record) written, the folder fsynced and
// renamed to views/<scene>/<v>. A re-run of the same command keeps every complete view
// (checked against its record: scene content, settings, file sizes), deletes interrupted
// writes, renders only what is missing and rebuilds manifest.json. manifest.json is deleted
// while views are missing, so its presence means the run finished.
//
// Parallelism: views run concurrently (up to `views_in_flight`) on oneTBB and each render
// is itself parallel; tbb::global_control caps the process at `threads`. Output never
// depends on either.
#include <cstddef>
#include <filesystem>
#include <vector>

#include <nlohmann/json.hpp>

#include "phyir/dataset/settings.h"
#include "phyir/dataset/shard.h"

namespace phyir::dataset {

struct GenerateOptions {
  std::filesystem::path scenes_dir;
  std::filesystem::path out_dir;
  DatasetSettings settings;
  Shard shard;
  int threads = 0;          // 0 = all cores
  int views_in_flight = 0;  // 0 = as many as threads
  bool progress = true;
};

struct GenerateSummary {
  size_t views = 0;     // views of this shard
  size_t rendered = 0;  // rendered by this run
  size_t kept = 0;      // already complete, kept
  double seconds = 0.0;
  double views_per_hour = 0.0;  // rendered / wall time of the rendering phase
};

// Throws phyir::Error on bad settings, a changed scene under existing views, another process
// holding the folder, or views that failed (listed; the complete ones are kept and a re-run
// retries the rest).
GenerateSummary generate_dataset(const GenerateOptions& options);

// render.json as run_render_job returns it, split into what is a pure function of the
// inputs (returned) and the wall-clock part (moved to *timing): every key named "timings",
// "threads", "seconds", "*_seconds" or "*per_second", at any depth.
nlohmann::json split_timing(nlohmann::json report, nlohmann::json* timing);

}  // namespace phyir::dataset
