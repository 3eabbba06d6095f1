// Debian's sweethome3d-furniture (five .sh3f libraries, 820 models), when installed: every
// catalog opens, every model loads to finite, non-empty geometry whose bounding box is the
// catalog size. Skipped when /usr/share/sweethome3d/furniture is absent.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <map>
#include <mutex>
#include <regex>
#include <string>
#include <thread>
#include <vector>

#include "phyir/core/error.h"
#include "phyir/core/stopwatch.h"
#include "phyir/scenes/asset_library.h"

namespace phyir::scenes {
namespace {

bool has_real_library() {
  std::error_code ec;
  return std::filesystem::is_directory(kDefaultAssetDir, ec);
}

// A model's box against its catalog size: metres, 1e-4 as the task states (0.1 mm; float
// positions of a 2 m model are good to ~1e-7).
constexpr float kBoxTolerance = 1e-4f;

std::string check_model(const AssetEntry& entry, const AssetModel& model) {
  if (model.triangle_count() == 0) return "no triangles";
  for (const AssetMesh& mesh : model.meshes) {
    for (size_t i = 0; i < mesh.positions.size(); ++i) {
      const glm::vec3 p = mesh.positions[i], n = mesh.normals[i];
      if (!std::isfinite(p.x + p.y + p.z) || !std::isfinite(n.x + n.y + n.z)) return "non-finite vertex";
      if (std::abs(glm::length(n) - 1.0f) > 1e-3f) return "normal not unit";
    }
    for (uint32_t index : mesh.indices) {
      if (index >= mesh.positions.size()) return "index out of range";
    }
  }
  const glm::vec3 lo = model.bounds_min(), hi = model.bounds_max();
  const glm::vec3 expected_lo(-0.5f * entry.size_m.x, 0.0f, -0.5f * entry.size_m.z);
  const glm::vec3 expected_hi(0.5f * entry.size_m.x, entry.size_m.y, 0.5f * entry.size_m.z);
  const bool flat = std::any_of(model.warnings.begin(), model.warnings.end(),
                                [](const std::string& w) { return w.rfind("flat along", 0) == 0; });
  for (int axis = 0; axis < 3 && !flat; ++axis) {
    if (std::abs(lo[axis] - expected_lo[axis]) > kBoxTolerance || std::abs(hi[axis] - expected_hi[axis]) > kBoxTolerance) {
      return "bounds " + std::to_string(lo[axis]) + ".." + std::to_string(hi[axis]) + " on axis " + "xyz"[axis];
    }
  }
  return "";
}

// A warning without its file names, material names and numbers, to count warnings by kind.
std::string warning_kind(const std::string& warning) {
  static const std::regex quoted("'[^']*'|\\[[^\\]]*\\]|[0-9]+");
  std::string kind = std::regex_replace(warning, quoted, "_");
  const size_t colon = kind.find(".obj: ");
  return colon == std::string::npos ? kind : kind.substr(colon + 6);
}

TEST(AssetRealLibrary, OpensEveryCatalog) {
  if (!has_real_library()) GTEST_SKIP() << kDefaultAssetDir << " absent (Debian package sweethome3d-furniture)";
  const Stopwatch watch;
  const AssetLibrary library = AssetLibrary::open(kDefaultAssetDir);
  std::printf("opened %zu archives, %zu entries in %.3f s\n", library.archives().size(), library.entries().size(),
              watch.seconds());
  EXPECT_EQ(library.archives().size(), 5u);
  EXPECT_EQ(library.entries().size(), 820u);  // sweethome3d-furniture 1.8
  EXPECT_TRUE(library.duplicate_ids().empty());
  for (const auto& [category, count] : library.category_counts()) std::printf("  %-18s %zu\n", category.c_str(), count);
  EXPECT_EQ(library.category_counts().at("Living room"), 147u);
  EXPECT_EQ(library.category_counts().at("Lights"), 34u);
  EXPECT_EQ(library.in_category("Doors and windows").size(), 35u);
  size_t lights = 0, openings = 0;
  for (const AssetEntry& e : library.entries()) {
    lights += e.is_light();
    openings += e.is_door_or_window;
    EXPECT_FALSE(e.licence.empty()) << e.id;
  }
  EXPECT_EQ(lights, 34u);
  EXPECT_EQ(openings, 33u);
  const size_t notes = std::count_if(library.entries().begin(), library.entries().end(),
                                     [](const AssetEntry& e) { return !e.licence_file.empty(); });
  std::printf("%zu entries have their own licence note\n", notes);
  EXPECT_GT(notes, 100u);  // the Blend Swap models
}

float nearest_vertex(const AssetModel& model, glm::vec3 p) {
  float nearest = 1e9f;
  for (const AssetMesh& mesh : model.meshes) {
    for (const glm::vec3& v : mesh.positions) nearest = std::min(nearest, glm::length(v - p));
  }
  return nearest;
}

// The catalog's lightSourceY counts from the front (Sweet Home 3D places a source at
// depth/2 - y in its 3D z): lamps whose bulbs sit well in front of or behind their centre
// have geometry at the sources as placed, not at their mirror images behind.
TEST(AssetRealLibrary, LightSourcesSitOnTheirLamps) {
  if (!has_real_library()) GTEST_SKIP() << kDefaultAssetDir << " absent (Debian package sweethome3d-furniture)";
  const AssetLibrary library = AssetLibrary::open(kDefaultAssetDir);
  for (const char* id : {"Kator Legaz#wall-lamp-artwork", "Kator Legaz#flashlight", "Kator Legaz#track-lights",
                         "Scopia#desk_lamp1", "Scopia#desk_lamp2", "Blend Swap CC-0#lamp2"}) {
    const AssetEntry& lamp = library.at(id);
    const AssetModel model = load_model(lamp);
    for (const AssetLightSource& source : lamp.light_sources) {
      const glm::vec3 placed = source.position(lamp.size_m);
      const glm::vec3 mirrored(placed.x, placed.y, -placed.z);
      EXPECT_LT(nearest_vertex(model, placed), 0.03f) << id;  // a bulb inside its shade
      EXPECT_LT(nearest_vertex(model, placed), nearest_vertex(model, mirrored)) << id;
    }
  }
}

// The front faces +Z: a seat's backrest (its vertices in the top 30% of its height) lies
// behind its centre. 75 of the 76 sofas, armchairs and chairs; the baby high chair's tray
// stands in front.
TEST(AssetRealLibrary, SeatsFaceFront) {
  if (!has_real_library()) GTEST_SKIP() << kDefaultAssetDir << " absent (Debian package sweethome3d-furniture)";
  const AssetLibrary library = AssetLibrary::open(kDefaultAssetDir);
  size_t behind = 0, seats = 0;
  for (const AssetEntry& e : library.entries()) {
    std::string name = e.name;
    std::transform(name.begin(), name.end(), name.begin(), [](unsigned char c) { return std::tolower(c); });
    const bool seat = name.find("sofa") != std::string::npos || name.find("chair") != std::string::npos;
    if (!seat || name.find("deck") != std::string::npos) continue;
    const AssetModel model = load_model(e);
    double z = 0.0;
    size_t count = 0;
    for (const AssetMesh& mesh : model.meshes) {
      for (const glm::vec3& p : mesh.positions) {
        if (p.y <= 0.7f * e.size_m.y) continue;
        z += p.z;
        ++count;
      }
    }
    ++seats;
    if (count > 0 && z < 0.0) {
      ++behind;
    } else {
      std::printf("  backrest not behind: %s\n", e.id.c_str());
    }
  }
  std::printf("%zu of %zu seats have their backrest at -Z\n", behind, seats);
  EXPECT_GE(seats, 70u);
  EXPECT_GE(behind + 2, seats);
}

// Loads every model on two threads; a failure is reported with its reason, never a crash.
TEST(AssetRealLibrary, LoadsEveryModel) {
  if (!has_real_library()) GTEST_SKIP() << kDefaultAssetDir << " absent (Debian package sweethome3d-furniture)";
  const AssetLibrary library = AssetLibrary::open(kDefaultAssetDir);
  const std::vector<AssetEntry>& entries = library.entries();
  std::atomic<size_t> next{0}, triangles{0}, with_warnings{0}, textures{0};
  std::mutex mutex;
  std::vector<std::string> failures;
  std::map<std::string, size_t> warnings_by_kind;
  const Stopwatch watch;
  const auto work = [&] {
    for (size_t i = next++; i < entries.size(); i = next++) {
      std::string problem;
      try {
        const AssetModel model = load_model(entries[i]);
        problem = check_model(entries[i], model);
        triangles += model.triangle_count();
        textures += model.textures.size();
        with_warnings += !model.warnings.empty();
        const std::lock_guard<std::mutex> lock(mutex);
        for (const std::string& w : model.warnings) ++warnings_by_kind[warning_kind(w).substr(0, 100)];
      } catch (const Error& e) {
        problem = e.what();
      }
      if (!problem.empty()) {
        const std::lock_guard<std::mutex> lock(mutex);
        failures.push_back(entries[i].id + ": " + problem);
      }
    }
  };
  std::thread other(work);
  work();
  other.join();
  std::printf("loaded %zu models on 2 threads in %.1f s: %zu triangles, %zu textures, %zu with warnings, %zu failed\n",
              entries.size(), watch.seconds(), triangles.load(), textures.load(), with_warnings.load(),
              failures.size());
  for (const auto& [kind, count] : warnings_by_kind) std::printf("  %5zu x warning: %s\n", count, kind.c_str());
  for (const std::string& f : failures) std::printf("  FAILED %s\n", f.c_str());
  EXPECT_TRUE(failures.empty());
}

}  // namespace
}  // namespace phyir::scenes
