#pragma once
// Shared by the dataset tests: a fresh folder per test, mini rooms, and tiny datasets
// rendered with the library (no probes unless asked: a view then takes ~0.1 s).
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <string>

#include "phyir/core/atomic_file.h"
#include "phyir/core/log.h"
#include "phyir/core/progress.h"
#include "phyir/dataset/generate.h"
#include "phyir/dataset/settings.h"
#include "phyir/scenes/room_generator.h"

namespace phyir::dataset::test {

namespace fs = std::filesystem;

// Silences progress lines and info logs once per test binary.
struct QuietEnvironment : ::testing::Environment {
  void SetUp() override {
    Progress::set_enabled(false);
    init_logging();
    set_log_level("warn");
  }
};

// Registered once per binary (an inline variable is one object across translation units).
inline ::testing::Environment* const kQuietEnvironment = ::testing::AddGlobalTestEnvironment(new QuietEnvironment);

// <temp>/phyir_dataset_test_<pid>/<suite>.<test>, emptied.
inline fs::path fresh_test_dir() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const fs::path dir = fs::temp_directory_path() / ("phyir_dataset_test_" + std::to_string(::getpid())) /
                       (std::string(info->test_suite_name()) + "." + info->name());
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// `count` generated rooms room_0 .. in dir/rooms.
inline fs::path make_rooms(const fs::path& dir, int count, scenes::RoomPreset preset = scenes::RoomPreset::Mini,
                           uint64_t seed = 1) {
  const fs::path rooms = dir / "rooms";
  for (int i = 0; i < count; ++i) scenes::generate_room(rooms, i, seed, preset);
  return rooms;
}

inline DatasetSettings tiny_settings(int views_per_scene, bool probes = false) {
  DatasetSettings s = preset_settings("tiny");
  s.views_per_scene = views_per_scene;
  s.probes = probes;
  return s;
}

inline GenerateSummary generate(const fs::path& rooms, const fs::path& out, const DatasetSettings& s,
                                Shard shard = {}) {
  GenerateOptions o;
  o.scenes_dir = rooms;
  o.out_dir = out;
  o.settings = s;
  o.shard = shard;
  o.threads = 2;
  o.progress = false;
  return generate_dataset(o);
}

// Every regular file under `dir` except timing.json, as relative path -> bytes.
inline std::map<std::string, std::string> tree(const fs::path& dir) {
  std::map<std::string, std::string> files;
  for (const auto& entry : fs::recursive_directory_iterator(dir))
    if (entry.is_regular_file() && entry.path().filename() != "timing.json")
      files[fs::relative(entry.path(), dir).generic_string()] = read_file(entry.path());
  return files;
}

inline void flip_byte(const fs::path& path, size_t offset) {
  std::fstream f(path, std::ios::in | std::ios::out | std::ios::binary);
  f.seekg(static_cast<std::streamoff>(offset));
  char c = 0;
  f.get(c);
  f.seekp(static_cast<std::streamoff>(offset));
  f.put(static_cast<char>(c ^ 0x5a));
}

}  // namespace phyir::dataset::test
