#include "phyir/dataset/merge.h"

#include "phyir/view/view_record.h"

#include <algorithm>
#include <map>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "phyir/core/atomic_file.h"
#include "phyir/core/error.h"
#include "phyir/core/log.h"
#include "phyir/dataset/layout.h"
#include "phyir/dataset/manifest.h"

namespace phyir::dataset {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

std::string list_some(const std::vector<std::string>& items, size_t limit = 5) {
  std::string out;
  for (size_t i = 0; i < items.size() && i < limit; ++i) out += (i ? ", " : "") + items[i];
  if (items.size() > limit) out += fmt::format(", ... ({} in all)", items.size());
  return out;
}

bool same_file(const fs::path& a, const fs::path& b) {
  std::error_code ec;
  return fs::equivalent(a, b, ec);
}

// Every shard's manifest, read and cross-checked, and the union of their scenes and views.
struct ShardSet {
  std::vector<Manifest> manifests;
  std::string first_name;
  std::string first_settings;                                   // settings.json's bytes
  std::map<std::string, std::pair<json, std::string>> scenes;  // name -> (record, shard dir)
  std::map<std::string, std::string> owner;                    // view id -> shard dir
  std::map<int, std::string> shard_index_owner;
  std::vector<const json*> views;

  const Manifest& first() const { return manifests.front(); }
};

// One shard against the first: same settings, scene list and partition; no shard index twice.
void check_shard_header(ShardSet& set, const Manifest& m, const fs::path& dir) {
  const Manifest& first = set.first();
  const std::string name = dir.string(), first_name = set.first_name;
  const std::string difference = describe_difference(first.settings, m.settings, "settings");
  if (!difference.empty())
    fail("dataset merge: {} and {} were generated with different settings ({}); shards of one dataset must come "
         "from one command",
         first_name, name, difference);
  if (read_file(dir / kSettingsFile) != set.first_settings)
    fail("dataset merge: {} and {} have different {} (another phyir version?)", first_name, name, kSettingsFile);
  if (m.scene_names != first.scene_names)
    fail("dataset merge: {} and {} were generated from different scene lists ({} vs {} scenes; {})", first_name, name,
         first.scene_names.size(), m.scene_names.size(),
         describe_difference(json(first.scene_names), json(m.scene_names), "scene_names"));
  if (m.scenes_dir != first.scenes_dir)
    spdlog::warn("dataset merge: {} names the scenes folder '{}', {} '{}'; the merged manifest uses '{}'", first_name,
                 first.scenes_dir, name, m.scenes_dir, first.scenes_dir);
  if (m.shard.count != first.shard.count)
    fail("dataset merge: {} is shard {} but {} is shard {}: they come from different partitions of the views and cannot be merged", first_name,
         shard_name(first.shard), name, shard_name(m.shard));
  if (auto [it, fresh] = set.shard_index_owner.emplace(m.shard.index, name); !fresh)
    fail("dataset merge: {} and {} are both shard {}", it->second, name, shard_name(m.shard));
}

// One shard's scenes (equal where shared) and views (none shared) into the union.
void add_shard_content(ShardSet& set, const Manifest& m, const std::string& name) {
  for (const json& s : m.scenes) {
    const std::string scene = s.at("name").get<std::string>();
    auto [it, fresh] = set.scenes.emplace(scene, std::make_pair(s, name));
    if (!fresh && it->second.first != s)
      fail("dataset merge: scene {} differs between {} and {} ({}); were the scenes changed between shard runs?",
           scene, it->second.second, name, describe_difference(it->second.first, s, scene));
  }
  std::vector<std::string> overlap;
  for (const json& v : m.views) {
    const std::string id = v.at("id").get<std::string>();
    if (auto [it, fresh] = set.owner.emplace(id, name); !fresh) overlap.push_back(id + " (" + it->second + ")");
    set.views.push_back(&v);
  }
  if (!overlap.empty())
    fail("dataset merge: {} shares {} view(s) with other shards: {}", name, overlap.size(), list_some(overlap));
}

// Every view of the dataset in some shard.
void check_complete(const ShardSet& set) {
  const Manifest& first = set.first();
  std::vector<std::string> missing;
  const int K = first.views_per_scene();
  for (const std::string& scene : first.scene_names)
    for (int k = 0; k < K; ++k)
      if (!set.owner.count(view_id(scene, k, K))) missing.push_back(view_id(scene, k, K));
  if (missing.empty()) return;
  std::vector<std::string> absent;
  for (int i = 0; i < first.shard.count; ++i)
    if (!set.shard_index_owner.count(i)) absent.push_back(fmt::format("{}/{}", i, first.shard.count));
  fail("dataset merge: {} of {} views are in no shard given: {}{}", missing.size(), first.views_total(),
       list_some(missing), absent.empty() ? std::string() : "; shard(s) not given: " + list_some(absent, 20));
}

// Reads and cross-checks every manifest before OUT is touched.
void read_shards(ShardSet& set, const std::vector<fs::path>& shard_dirs) {
  for (const fs::path& d : shard_dirs) set.manifests.push_back(read_manifest(d));
  set.first_name = shard_dirs.front().string();
  set.first_settings = read_file(shard_dirs.front() / kSettingsFile);
  for (size_t i = 0; i < set.manifests.size(); ++i) {
    check_shard_header(set, set.manifests[i], shard_dirs[i]);
    add_shard_content(set, set.manifests[i], shard_dirs[i].string());
  }
  check_complete(set);
}

// OUT (created and locked) cleaned; a dataset of other settings already there fails.
void prepare_merge_folder(const fs::path& out, const std::string& first_settings) {
  std::error_code ec;
  remove_temporaries(out);
  fs::remove(out / kManifestFile, ec);
  const std::string out_settings = (out / kSettingsFile).string();
  if (fs::exists(out_settings, ec) && read_file(out_settings) != first_settings)
    fail("dataset merge: {} already holds a dataset with other settings; merge into a new folder", out.string());
}

// True when an earlier (interrupted) run merged the view already; else clears its target.
bool already_merged(const fs::path& target, const json& view) {
  std::error_code ec;
  if (!fs::exists(target / kViewRecordFile, ec)) return false;
  json existing;
  try {
    existing = view::read_view_json(target);
  } catch (const Error&) {  // unreadable: merged again
  }
  if (existing == view) return true;
  fs::remove_all(target, ec);
  return false;
}

// The view's files hard-linked (or copied) into a temporary folder renamed into place.
void place_view(const fs::path& source, const fs::path& target, const json& view, const std::string& shard,
                MergeSummary& summary) {
  std::error_code ec;
  const fs::path tmp = target.parent_path() / (kTemporaryPrefix + target.filename().string());
  fs::remove_all(tmp, ec);
  fs::create_directories(tmp, ec);
  if (ec) fail("{}: cannot create: {}", tmp.string(), ec.message());
  std::map<std::string, uint64_t> expected;
  for (const json& f : view.at("files")) expected[f.at("path").get<std::string>()] = f.at("size").get<uint64_t>();
  for (const fs::directory_entry& entry : fs::directory_iterator(source, ec)) {
    const std::string name = entry.path().filename().string();
    if (is_temporary_name(name)) continue;
    if (auto it = expected.find(name); it != expected.end() && entry.file_size() != it->second)
      fail("dataset merge: {}: {} bytes, its manifest says {}; run 'phyir dataset verify {}'", entry.path().string(),
           entry.file_size(), it->second, shard);
    fs::create_hard_link(entry.path(), tmp / name, ec);
    if (!ec) {
      ++summary.linked_files;
      continue;
    }
    fs::copy_file(entry.path(), tmp / name, fs::copy_options::overwrite_existing, ec);
    if (ec) fail("dataset merge: cannot copy {} to {}: {}", entry.path().string(), (tmp / name).string(), ec.message());
    commit_file(tmp / name, tmp / name);  // fsync the copy
    ++summary.copied_files;
  }
  for (const auto& [name, size] : expected)
    if (!fs::exists(tmp / name, ec)) fail("dataset merge: {} is missing from {}", name, source.string());
  sync_folder(tmp);
  fs::rename(tmp, target, ec);
  if (ec) fail("dataset merge: cannot move {} into place: {}", target.string(), ec.message());
  sync_folder(target.parent_path());
}

// settings.json, then the manifest (last: its presence means the merge finished).
void write_merged_records(const fs::path& out, const ShardSet& set) {
  write_file_atomic(out / kSettingsFile, set.first_settings);
  const Manifest& first = set.first();
  Manifest merged;
  merged.settings = first.settings;
  merged.scenes_dir = first.scenes_dir;
  merged.shard = {0, 1};
  merged.scene_names = first.scene_names;
  for (const auto& [name, record] : set.scenes) merged.scenes.push_back(record.first);
  for (const json* v : set.views) merged.views.push_back(*v);
  write_manifest(out, merged);
}

}  // namespace

MergeSummary merge_shards(const fs::path& out, const std::vector<fs::path>& shard_dirs) {
  if (shard_dirs.empty()) fail("dataset merge: give at least one shard folder after OUT");
  for (const fs::path& d : shard_dirs)
    if (same_file(d, out)) fail("dataset merge: OUT {} is also given as a shard; merge into a new folder", out.string());
  ShardSet set;
  read_shards(set, shard_dirs);

  std::error_code ec;
  fs::create_directories(out / kViewsFolder, ec);
  if (ec) fail("{}: cannot create: {}", out.string(), ec.message());
  const FolderLock lock(out, "merge");
  prepare_merge_folder(out, set.first_settings);
  std::sort(set.views.begin(), set.views.end(), [&](const json* a, const json* b) {
    const std::string sa = a->at("scene").at("name"), sb = b->at("scene").at("name");
    return sa != sb ? sa < sb : a->at("index").get<int>() < b->at("index").get<int>();
  });
  MergeSummary summary;
  summary.views = set.views.size();
  for (const json* view : set.views) {
    const std::string& shard = set.owner.at(view->at("id").get<std::string>());
    const fs::path relative = view->at("dir").get<std::string>();
    if (already_merged(out / relative, *view)) {
      ++summary.kept;
      continue;
    }
    place_view(fs::path(shard) / relative, out / relative, *view, shard, summary);
    ++summary.merged;
  }
  write_merged_records(out, set);
  spdlog::info("dataset merge: {} views from {} shard(s) into {} ({} placed, {} already there; {} files linked, {} "
               "copied)",
               summary.views, shard_dirs.size(), out.string(), summary.merged, summary.kept, summary.linked_files,
               summary.copied_files);
  return summary;
}

}  // namespace phyir::dataset
