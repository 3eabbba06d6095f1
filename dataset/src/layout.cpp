#include "phyir/dataset/layout.h"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <map>

#include <fmt/format.h>

#include "phyir/core/error.h"
#include "phyir/core/setting_error.h"
#include "phyir/core/log.h"
#include "phyir/dataset/checksum.h"

namespace phyir::dataset {

namespace fs = std::filesystem;

std::vector<SceneFile> list_scenes(const fs::path& dir) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) fail_setting("scenes_dir", "{}: not a folder", dir.string());
  std::vector<SceneFile> scenes;
  std::map<std::string, std::string> by_stem;
  for (const fs::directory_entry& entry : fs::directory_iterator(dir)) {
    const std::string file = entry.path().filename().string();
    const std::string ext = entry.path().extension().string();
    if (file.empty() || file[0] == '.' || (ext != ".gltf" && ext != ".glb")) continue;
    if (!entry.is_regular_file()) continue;
    const std::string stem = entry.path().stem().string();
    if (auto it = by_stem.find(stem); it != by_stem.end())
      fail_setting("scenes_dir", "{}: '{}' and '{}' would share the views folder '{}'; rename one", dir.string(), it->second, file, stem);
    by_stem[stem] = file;
    scenes.push_back({stem, file});
  }
  if (scenes.empty()) fail_setting("scenes_dir", "{}: no .gltf or .glb files", dir.string());
  std::sort(scenes.begin(), scenes.end(), [](const SceneFile& a, const SceneFile& b) { return a.name < b.name; });
  return scenes;
}

std::string view_name(int index, int views_per_scene) {
  const int digits = std::max<int>(3, int(std::to_string(std::max(views_per_scene - 1, 0)).size()));
  return fmt::format("v{:0{}d}", index, digits);
}

std::string view_id(const std::string& scene, int index, int views_per_scene) {
  return scene + "/" + view_name(index, views_per_scene);
}

fs::path view_folder(const std::string& scene, int index, int views_per_scene) {
  return fs::path(kViewsFolder) / scene / view_name(index, views_per_scene);
}

uint64_t view_seed(uint64_t seed, const std::string& scene, int index) {
  return hash64(fmt::format("phyir-dataset view|{}|{}|{}", seed, scene, index)) >> 11;
}

bool is_temporary_name(const std::string& name) {
  return name.rfind(kTemporaryPrefix, 0) == 0 || (name.size() > 1 && name[0] == '.' && name.find(".partial-") != std::string::npos);
}

size_t remove_temporaries(const fs::path& root) {
  size_t removed = 0;
  std::error_code ec;
  const auto sweep = [&](const fs::path& folder, auto&& recurse, int depth) -> void {
    if (!fs::is_directory(folder, ec)) return;
    std::vector<fs::path> children;
    for (const fs::directory_entry& entry : fs::directory_iterator(folder, ec)) children.push_back(entry.path());
    for (const fs::path& child : children) {
      if (is_temporary_name(child.filename().string())) {
        spdlog::debug("removing interrupted write {}", child.string());
        fs::remove_all(child, ec);
        if (ec) fail("{}: cannot remove an interrupted write: {}", child.string(), ec.message());
        ++removed;
      } else if (depth > 0 && fs::is_directory(child, ec)) {
        recurse(child, recurse, depth - 1);
      }
    }
  };
  sweep(root, sweep, 0);
  sweep(root / kViewsFolder, sweep, 2);  // views/.tmp-*, views/<scene>/.tmp-*, views/<scene>/<v>/.*.partial-*
  return removed;
}

void sync_folder(const fs::path& folder) {
  const int fd = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY);
  if (fd < 0) return;
  ::fsync(fd);
  ::close(fd);
}

FolderLock::FolderLock(const fs::path& dir, const std::string& command) {
  const fs::path path = dir / kLockFile;
  fd_ = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd_ < 0) fail("{}: cannot open the lock file: {}", path.string(), std::strerror(errno));
  if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
    const int error = errno;
    ::close(fd_);
    fd_ = -1;
    if (error == EWOULDBLOCK)
      fail("{}: another phyir process is writing this folder (it holds {}); wait for it or stop it, then run "
           "'phyir dataset {}' again",
           dir.string(), path.string(), command);
    fail("{}: cannot lock: {}", path.string(), std::strerror(error));
  }
}

FolderLock::~FolderLock() {
  if (fd_ >= 0) ::close(fd_);  // closing drops the flock
}

}  // namespace phyir::dataset
