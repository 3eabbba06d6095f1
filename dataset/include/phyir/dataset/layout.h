#pragma once
// The dataset's folder layout and names (docs/dataset.md):
//
//   OUT/settings.json              the settings (written first; a re-run must match it)
//   OUT/manifest.json              every view, file, checksum and split (written last)
//   OUT/views/<scene>/<vNNN>/      one folder per view, renamed into place when whole
//   OUT/.lock                      held (flock) by the one process writing OUT
//
// A view is complete exactly when its folder exists under its final name: it is rendered
// into views/<scene>/.tmp-<vNNN>, checked, and renamed. Anything named .tmp-* or
// .*.partial-* is an interrupted write and is deleted by the next run.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "phyir/view/view_files.h"
#include "phyir/view/view_record.h"

namespace phyir::dataset {

// The view folder's own files and the manifest's name: the view module's (view/view_files.h).
using view::kInputFile;
using view::kManifestFile;
using view::kRenderRecordFile;
using view::kTemporaryPrefix;
using view::kTimingFile;
using view::kViewRecordFile;
inline constexpr const char* kSettingsFile = "settings.json";
inline constexpr const char* kLockFile = ".lock";
inline constexpr const char* kViewsFolder = "views";

// A glTF file of the scenes folder: `name` is its stem (the folder its views go in), `file`
// its file name.
struct SceneFile {
  std::string name;
  std::string file;
};

// The .gltf and .glb files directly in `dir`, sorted by name (byte order). Throws
// phyir::Error when there are none, or two share a stem.
std::vector<SceneFile> list_scenes(const std::filesystem::path& dir);

// "v000" (at least three digits, more when views_per_scene needs them).
std::string view_name(int index, int views_per_scene);
// "<scene>/v000": the view's id in the manifest and its folder under views/.
std::string view_id(const std::string& scene, int index, int views_per_scene);
std::filesystem::path view_folder(const std::string& scene, int index, int views_per_scene);  // views/<scene>/v000

// The render seed of a view: 53 bits of SHA-256("phyir-dataset view|<seed>|<scene>|<index>"),
// independent of shards, threads and the other scenes.
uint64_t view_seed(uint64_t seed, const std::string& scene, int index);

// True for names of interrupted writes (.tmp-*, .*.partial-*).
bool is_temporary_name(const std::string& name);

// Deletes every interrupted write under `root` (its own files and views/*/, views/*/*/),
// returns how many. Call only while holding the folder's lock.
size_t remove_temporaries(const std::filesystem::path& root);

// fsync a folder so a rename inside it survives a power cut.
void sync_folder(const std::filesystem::path& folder);

// An exclusive flock on <dir>/.lock for the life of the object: a second process writing
// the same folder fails at once with a message naming it. The kernel drops the lock when the
// process dies (kill -9 included), so a crashed run never blocks the next one.
class FolderLock {
 public:
  FolderLock(const std::filesystem::path& dir, const std::string& command);
  ~FolderLock();
  FolderLock(const FolderLock&) = delete;
  FolderLock& operator=(const FolderLock&) = delete;

 private:
  int fd_ = -1;
};

}  // namespace phyir::dataset
