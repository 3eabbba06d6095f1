#include "phyir/dataset/verify.h"

#include "phyir/view/view_record.h"

#include <tbb/global_control.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>
#include <set>
#include <vector>

#include <fmt/format.h>

#include "phyir/core/atomic_file.h"
#include "phyir/core/error.h"
#include "phyir/core/image_io.h"
#include "phyir/core/progress.h"
#include "phyir/dataset/checksum.h"
#include "phyir/dataset/layout.h"
#include "phyir/dataset/manifest.h"
#include "phyir/dataset/split.h"

namespace phyir::dataset {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

bool is_image(const std::string& name) {
  const std::string ext = fs::path(name).extension().string();
  return ext == ".exr" || ext == ".png";
}

// Safe relative path: no absolute paths, no "..", so a manifest cannot point outside DIR.
bool is_safe_relative(const std::string& path) {
  const fs::path p(path);
  if (p.empty() || p.is_absolute()) return false;
  for (const fs::path& part : p)
    if (part == "..") return false;
  return true;
}

}  // namespace

FileCheck inspect_file(const fs::path& folder, const std::string& name) {
  FileCheck check;
  const fs::path path = folder / name;
  std::string bytes;
  try {
    bytes = read_file(path);
  } catch (const Error& e) {
    check.problem = fmt::format("cannot be read ({})", e.what());
    return check;
  }
  check.record = {{"path", name}, {"size", bytes.size()}, {"sha256", sha256_hex(bytes)}};
  if (!is_image(name)) return check;
  try {
    const std::vector<unsigned char> data(bytes.begin(), bytes.end());
    Image image;
    try {
      image = read_image_from_memory(data, path.string());
    } catch (const Error&) {
      image = read_image(path);  // formats OIIO cannot read from memory
    }
    check.record["width"] = image.width;
    check.record["height"] = image.height;
    check.record["channels"] = image.channels;
    if (fs::path(name).extension() == ".exr" &&
        !std::all_of(image.pixels.begin(), image.pixels.end(), [](float v) { return std::isfinite(v); }))
      check.problem = "holds NaN or Inf values";
  } catch (const Error& e) {
    check.problem = fmt::format("cannot be decoded ({})", e.what());
  }
  return check;
}

namespace {

// Checks a dataset against its manifest; problems are collected from many threads.
class DatasetVerifier {
 public:
  DatasetVerifier(const fs::path& dir, const Manifest& manifest) : dir_(dir), manifest_(manifest) {}

  VerifyReport run(int threads) {
    check_header();
    const int n = threads > 0 ? threads : tbb::info::default_concurrency();
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, n);
    Progress progress("verifying", manifest_.views.size(), "views");
    tbb::parallel_for(size_t(0), manifest_.views.size(), [&](size_t i) {
      if (check_view(manifest_.views[i])) progress.advance();
    });
    progress.finish();
    check_interrupted_writes();
    report_.views = manifest_.views.size();
    report_.files = files_;
    report_.bytes = bytes_;
    std::sort(report_.problems.begin(), report_.problems.end());
    report_.damaged_views.assign(damaged_.begin(), damaged_.end());
    return report_;
  }

 private:
  void problem(std::string text) {
    std::lock_guard<std::mutex> lock(mutex_);
    report_.problems.push_back(std::move(text));
  }

  void damage(const std::string& view_dir, std::string text) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      damaged_.insert(view_dir);
    }
    problem(std::move(text));
  }

  // The header: scenes in one split each, views in their scene's split, ids unique.
  void check_header() {
    std::map<std::string, std::string> split_of;
    for (const json& s : manifest_.scenes) {
      const std::string name = s.value("name", "");
      const std::string split = s.value("split", "");
      if (split_of.count(name) && split_of[name] != split)
        problem(fmt::format("manifest: scene {} is listed in two splits ({} and {})", name, split_of[name], split));
      split_of[name] = split;
    }
    std::set<std::string> ids;
    for (const json& v : manifest_.views) {
      const std::string id = v.value("id", "");
      if (!ids.insert(id).second) problem(fmt::format("manifest: view {} is listed twice", id));
      const std::string scene = v.at("scene").value("name", "");
      if (!split_of.count(scene))
        problem(fmt::format("manifest: view {} belongs to scene {}, which is not in \"scenes\"", id, scene));
      else if (split_of[scene] != v.value("split", ""))
        problem(fmt::format("manifest: view {} is in split {} but its scene {} is in {}", id, v.value("split", ""),
                            scene, split_of[scene]));
    }
    if (manifest_.shard.whole() && manifest_.views.size() != manifest_.views_total())
      problem(fmt::format("manifest: {} views listed, but {} scenes x {} views per scene = {}", manifest_.views.size(),
                          manifest_.scene_names.size(), manifest_.views_per_scene(), manifest_.views_total()));
  }

  // One view folder; false when its dir is unsafe (not counted as verified).
  bool check_view(const json& view) {
    const std::string id = view.value("id", "?");
    const std::string dir_name = view.value("dir", "");
    if (!is_safe_relative(dir_name)) {
      problem(fmt::format("{}: dir '{}' is not a relative path inside the dataset", id, dir_name));
      return false;
    }
    const fs::path folder = dir_ / dir_name;
    std::error_code ec;
    if (!fs::is_directory(folder, ec)) {
      damage(dir_name, fmt::format("{}: missing view folder", (fs::path(dir_name)).string()));
      return true;
    }
    check_record(folder, dir_name, view);
    std::set<std::string> listed = {kViewRecordFile, kTimingFile};
    for (const json& f : view.at("files")) check_file(folder, dir_name, id, f, listed);
    for (const fs::directory_entry& entry : fs::directory_iterator(folder, ec)) {
      const std::string name = entry.path().filename().string();
      if (!listed.count(name))
        damage(dir_name, fmt::format("{}/{}: {} not in the manifest", dir_name, name,
                                     is_temporary_name(name) ? "interrupted write" : "file"));
    }
    return true;
  }

  // view.json must say what the manifest says.
  void check_record(const fs::path& folder, const std::string& dir_name, const json& view) {
    try {
      const json record = view::read_view_json(folder);
      if (record != view)
        damage(dir_name, fmt::format("{}/{}: differs from the manifest ({})", dir_name, kViewRecordFile,
                                     describe_difference(record, view, "view")));
    } catch (const std::exception& e) {
      damage(dir_name, fmt::format("{}/{}: unreadable: {}", dir_name, kViewRecordFile, e.what()));
    }
  }

  // One listed file: present, decodable, finite, of the recorded size, checksum and shape.
  void check_file(const fs::path& folder, const std::string& dir_name, const std::string& id, const json& f,
                  std::set<std::string>& listed) {
    const std::string name = f.value("path", "");
    listed.insert(name);
    const std::string shown = dir_name + "/" + name;
    std::error_code ec;
    if (!is_safe_relative(name)) return damage(dir_name, fmt::format("{}: file path '{}' leaves the view folder", id, name));
    if (!fs::exists(folder / name, ec)) return damage(dir_name, fmt::format("{}: missing", shown));
    const FileCheck check = inspect_file(folder, name);
    files_++;
    if (!check.problem.empty()) damage(dir_name, shown + ": " + check.problem);
    if (check.record.is_null()) return;
    bytes_ += check.record["size"].get<uint64_t>();
    if (check.record["size"] != f.value("size", json())) {
      damage(dir_name, fmt::format("{}: size {} bytes, the manifest says {}", shown, check.record["size"].dump(),
                                   f.value("size", json()).dump()));
    } else if (check.record["sha256"] != f.value("sha256", json())) {
      damage(dir_name, fmt::format("{}: sha256 {} does not match the manifest's {}", shown,
                                   check.record["sha256"].get<std::string>(), f.value("sha256", json()).dump()));
    }
    for (const char* key : {"width", "height", "channels"})
      if (check.record.contains(key) && check.record[key] != f.value(key, json()))
        damage(dir_name, fmt::format("{}: {} {} as decoded, the manifest says {}", shown, key,
                                     check.record[key].dump(), f.value(key, json()).dump()));
  }

  // Interrupted writes elsewhere (folders being renamed into place).
  void check_interrupted_writes() {
    std::error_code ec;
    if (!fs::is_directory(dir_ / kViewsFolder, ec)) return;
    for (const fs::directory_entry& scene : fs::directory_iterator(dir_ / kViewsFolder, ec))
      if (scene.is_directory(ec))
        for (const fs::directory_entry& entry : fs::directory_iterator(scene.path(), ec))
          if (is_temporary_name(entry.path().filename().string()))
            problem(fmt::format("{}: interrupted write left behind",
                                fs::relative(entry.path(), dir_, ec).generic_string()));
  }

  const fs::path& dir_;
  const Manifest& manifest_;
  VerifyReport report_;
  std::mutex mutex_;
  std::set<std::string> damaged_;
  std::atomic<size_t> files_{0};
  std::atomic<uint64_t> bytes_{0};
};

}  // namespace

VerifyReport verify_dataset(const fs::path& dir, int threads) {
  const Manifest manifest = read_manifest(dir);
  return DatasetVerifier(dir, manifest).run(threads);
}

size_t remove_damaged_views(const fs::path& dir, const VerifyReport& report) {
  const FolderLock lock(dir, "verify (removing damaged views)");
  std::error_code ec;
  fs::remove(dir / kManifestFile, ec);  // the dataset is incomplete from here on
  size_t removed = 0;
  for (const std::string& view : report.damaged_views) {
    const fs::path folder = dir / view;
    if (!is_safe_relative(view) || !fs::exists(folder, ec)) continue;
    const fs::path doomed = folder.parent_path() / (kTemporaryPrefix + folder.filename().string());
    fs::remove_all(doomed, ec);
    fs::rename(folder, doomed, ec);
    if (ec) fail("{}: cannot remove: {}", folder.string(), ec.message());
    fs::remove_all(doomed, ec);
    ++removed;
  }
  sync_folder(dir);
  return removed;
}

}  // namespace phyir::dataset
