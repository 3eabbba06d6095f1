// generate / verify / merge end to end on tiny datasets of mini rooms (no probes, so each
// view renders in a fraction of a second): splits by scene in the manifest, resume keeps
// complete views, changed settings or scenes are refused, verify finds each kind of damage,
// merged shards are byte-identical to the unsharded run and inconsistent shards are refused.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <map>
#include <set>

#include "dataset_test_helpers.h"
#include "phyir/core/error.h"
#include "phyir/dataset/layout.h"
#include "phyir/dataset/manifest.h"
#include "phyir/dataset/merge.h"
#include "phyir/dataset/verify.h"

namespace phyir::dataset {
namespace {

namespace fs = std::filesystem;
using ::testing::AllOf;
using ::testing::HasSubstr;
using nlohmann::json;

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

std::string all_problems(const VerifyReport& r) {
  std::string s;
  for (const auto& p : r.problems) s += p + "\n";
  return s;
}

void copy_tree(const fs::path& from, const fs::path& to) {
  fs::remove_all(to);
  fs::copy(from, to, fs::copy_options::recursive);
}

TEST(Pipeline, GenerateWritesAManifestWithSplitsByScene) {
  const auto dir = test::fresh_test_dir();
  const auto rooms = test::make_rooms(dir, 3);
  DatasetSettings s = test::tiny_settings(2);
  s.split = {0.34, 0.33, 0.33};
  const GenerateSummary first = test::generate(rooms, dir / "out", s);
  EXPECT_EQ(first.views, 6u);
  EXPECT_EQ(first.rendered, 6u);

  const Manifest m = read_manifest(dir / "out");
  ASSERT_EQ(m.views.size(), 6u);
  EXPECT_EQ(m.scene_names, (std::vector<std::string>{"room_0", "room_1", "room_2"}));
  std::map<std::string, std::string> split_of;
  for (const json& scene : m.scenes) split_of[scene["name"]] = scene["split"];
  std::map<std::string, std::set<std::string>> scenes_per_split;
  for (const json& v : m.views) {
    EXPECT_EQ(v["split"], split_of.at(v["scene"]["name"])) << v["id"];
    scenes_per_split[v["split"]].insert(v["scene"]["name"]);
    EXPECT_EQ(v["settings_sha256"].get<std::string>().size(), 64u);
    EXPECT_TRUE(fs::exists(dir / "out" / v["dir"].get<std::string>() / "input.png"));
    EXPECT_TRUE(v["input"].contains("exposure_stops"));
  }
  size_t total = 0;
  for (const auto& [split, names] : scenes_per_split) total += names.size();
  EXPECT_EQ(total, 3u) << "a scene appears in two splits";
  EXPECT_EQ(m.views[0]["viewpoint"]["source"], "camera");
  EXPECT_TRUE(verify_dataset(dir / "out").ok());

  // The same command again: nothing to do, nothing rewritten.
  const auto before = test::tree(dir / "out");
  const GenerateSummary again = test::generate(rooms, dir / "out", s);
  EXPECT_EQ(again.rendered, 0u);
  EXPECT_EQ(again.kept, 6u);
  EXPECT_EQ(test::tree(dir / "out"), before);

  // Other settings into the same folder: refused, naming the difference.
  DatasetSettings other = s;
  other.spp = 8;
  EXPECT_THAT(error_of([&] { test::generate(rooms, dir / "out", other); }),
              AllOf(HasSubstr("other settings"), HasSubstr("spp")));
}

TEST(Pipeline, ResumeRendersOnlyMissingOrDamagedViewsAndRefusesChangedScenes) {
  const auto dir = test::fresh_test_dir();
  const auto rooms = test::make_rooms(dir, 1);
  const DatasetSettings s = test::tiny_settings(3);
  test::generate(rooms, dir / "ref", s);
  copy_tree(dir / "ref", dir / "out");
  // An unfinished run: one view missing, one half-written, one damaged, no manifest.
  fs::remove_all(dir / "out/views/room_0/v001");
  fs::create_directories(dir / "out/views/room_0/.tmp-v001");
  fs::remove(dir / "out/views/room_0/v002/depth.exr");
  fs::remove(dir / "out/manifest.json");
  const GenerateSummary resumed = test::generate(rooms, dir / "out", s);
  EXPECT_EQ(resumed.kept, 1u);
  EXPECT_EQ(resumed.rendered, 2u);
  EXPECT_EQ(test::tree(dir / "out"), test::tree(dir / "ref"));
  EXPECT_FALSE(fs::exists(dir / "out/views/room_0/.tmp-v001"));

  // The scene's buffer changes under complete views: refused, not silently mixed.
  test::flip_byte(rooms / "room_0.bin", 64);
  EXPECT_THAT(error_of([&] { test::generate(rooms, dir / "out", s); }),
              AllOf(HasSubstr("do not match the scenes"), HasSubstr("room_0.gltf")));
}

TEST(Pipeline, AnotherProcessHoldingTheFolderIsRefused) {
  const auto dir = test::fresh_test_dir();
  const auto rooms = test::make_rooms(dir, 1);
  fs::create_directories(dir / "out");
  const FolderLock held(dir / "out", "generate");
  EXPECT_THAT(error_of([&] { test::generate(rooms, dir / "out", test::tiny_settings(1)); }),
              HasSubstr("another phyir process"));
}

TEST(Pipeline, VerifyFindsEveryKindOfDamage) {
  const auto dir = test::fresh_test_dir();
  const auto rooms = test::make_rooms(dir, 1);
  test::generate(rooms, dir / "good", test::tiny_settings(1));
  ASSERT_TRUE(verify_dataset(dir / "good").ok()) << all_problems(verify_dataset(dir / "good"));
  const fs::path view = "views/room_0/v000";

  const auto damaged = [&](const std::string& name, const std::function<void(const fs::path&)>& damage) {
    const fs::path copy = dir / name;
    copy_tree(dir / "good", copy);
    damage(copy);
    const VerifyReport r = verify_dataset(copy);
    EXPECT_FALSE(r.ok()) << name;
    return all_problems(r);
  };
  // A flipped byte inside the image data: the checksum catches it even if the file decodes.
  EXPECT_THAT(damaged("flipped", [&](const fs::path& d) { test::flip_byte(d / view / "color.exr", 2000); }),
              AllOf(HasSubstr("views/room_0/v000/color.exr"), HasSubstr("sha256")));
  // A broken PNG header: OpenImageIO cannot decode it.
  EXPECT_THAT(damaged("undecodable", [&](const fs::path& d) { test::flip_byte(d / view / "input.png", 1); }),
              AllOf(HasSubstr("views/room_0/v000/input.png"), HasSubstr("cannot be decoded")));
  EXPECT_THAT(damaged("missing", [&](const fs::path& d) { fs::remove(d / view / "depth.exr"); }),
              HasSubstr("views/room_0/v000/depth.exr: missing"));
  EXPECT_THAT(damaged("truncated", [&](const fs::path& d) { fs::resize_file(d / view / "normal.exr", 50); }),
              HasSubstr("views/room_0/v000/normal.exr: size 50 bytes"));
  // The manifest's checksum edited (the file intact): a mismatch, and view.json disagrees.
  EXPECT_THAT(damaged("manifest",
                      [&](const fs::path& d) {
                        json j = json::parse(read_file(d / "manifest.json"));
                        j["views"][0]["files"][0]["sha256"] = std::string(64, '0');
                        write_file_atomic(d / "manifest.json", j.dump());
                      }),
              AllOf(HasSubstr("does not match the manifest"), HasSubstr("view.json: differs from the manifest")));
  EXPECT_THAT(damaged("stray", [&](const fs::path& d) { write_file_atomic(d / view / "extra.txt", "x"); }),
              HasSubstr("extra.txt: file not in the manifest"));
  EXPECT_THAT(damaged("interrupted", [&](const fs::path& d) { fs::create_directories(d / "views/room_0/.tmp-v001"); }),
              HasSubstr("views/room_0/.tmp-v001: interrupted write"));
  // No manifest at all: an unfinished run.
  EXPECT_THAT(error_of([&] {
                copy_tree(dir / "good", dir / "unfinished");
                fs::remove(dir / "unfinished/manifest.json");
                verify_dataset(dir / "unfinished");
              }),
              HasSubstr("has not finished"));
}

TEST(Pipeline, RemoveDamagedThenGenerateRepairsOnlyThoseViews) {
  const auto dir = test::fresh_test_dir();
  const auto rooms = test::make_rooms(dir, 1);
  const DatasetSettings s = test::tiny_settings(3);
  test::generate(rooms, dir / "good", s);
  copy_tree(dir / "good", dir / "out");
  test::flip_byte(dir / "out/views/room_0/v001/roughness.exr", 300);  // same size: only the checksum sees it
  const VerifyReport report = verify_dataset(dir / "out");
  ASSERT_EQ(report.damaged_views, (std::vector<std::string>{"views/room_0/v001"}));
  EXPECT_EQ(remove_damaged_views(dir / "out", report), 1u);
  EXPECT_FALSE(fs::exists(dir / "out/manifest.json"));
  const GenerateSummary repaired = test::generate(rooms, dir / "out", s);
  EXPECT_EQ(repaired.rendered, 1u);
  EXPECT_EQ(test::tree(dir / "out"), test::tree(dir / "good"));
}

class Merge : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = fs::temp_directory_path() / ("phyir_dataset_test_" + std::to_string(::getpid())) / "Merge";
    fs::remove_all(dir_);
    const auto rooms = test::make_rooms(dir_, 2);
    const DatasetSettings s = test::tiny_settings(2);
    test::generate(rooms, dir_ / "whole", s);
    test::generate(rooms, dir_ / "s0", s, {0, 2});
    test::generate(rooms, dir_ / "s1", s, {1, 2});
  }
  static void TearDownTestSuite() { fs::remove_all(dir_); }
  static fs::path dir_;
};
fs::path Merge::dir_;

TEST_F(Merge, ShardsMergeIntoTheUnshardedBytes) {
  EXPECT_EQ(read_manifest(dir_ / "s0").views.size(), 2u);
  EXPECT_EQ(read_manifest(dir_ / "s1").views.size(), 2u);
  const MergeSummary summary = merge_shards(dir_ / "merged", {dir_ / "s1", dir_ / "s0"});  // any order
  EXPECT_EQ(summary.views, 4u);
  EXPECT_EQ(test::tree(dir_ / "merged"), test::tree(dir_ / "whole"));
  EXPECT_TRUE(verify_dataset(dir_ / "merged").ok());
  // Merging again finishes an interrupted merge and changes nothing.
  fs::remove(dir_ / "merged/manifest.json");
  const MergeSummary again = merge_shards(dir_ / "merged", {dir_ / "s0", dir_ / "s1"});
  EXPECT_EQ(again.kept, 4u);
  EXPECT_EQ(test::tree(dir_ / "merged"), test::tree(dir_ / "whole"));
}

TEST_F(Merge, RefusesInconsistentShards) {
  const fs::path out = dir_ / "refused";
  EXPECT_THAT(error_of([&] { merge_shards(out, {dir_ / "s0"}); }),
              AllOf(HasSubstr("2 of 4 views are in no shard"), HasSubstr("room_1/v000"), HasSubstr("not given: 1/2")));
  EXPECT_THAT(error_of([&] { merge_shards(out, {dir_ / "s0", dir_ / "s0"}); }), HasSubstr("are both shard 0/2"));

  // Other settings in one shard.
  copy_tree(dir_ / "s1", dir_ / "s1_spp");
  json m = json::parse(read_file(dir_ / "s1_spp/manifest.json"));
  m["settings"]["render"]["spp"] = 16;
  write_file_atomic(dir_ / "s1_spp/manifest.json", m.dump());
  EXPECT_THAT(error_of([&] { merge_shards(out, {dir_ / "s0", dir_ / "s1_spp"}); }),
              AllOf(HasSubstr("different settings"), HasSubstr("settings.render.spp: 4 vs 16")));

  // Overlapping views: a shard 1/2 that also lists a view of shard 0.
  copy_tree(dir_ / "s1", dir_ / "s1_overlap");
  m = json::parse(read_file(dir_ / "s1_overlap/manifest.json"));
  m["views"].push_back(json::parse(read_file(dir_ / "s0/manifest.json"))["views"][0]);
  write_file_atomic(dir_ / "s1_overlap/manifest.json", m.dump());
  EXPECT_THAT(error_of([&] { merge_shards(out, {dir_ / "s0", dir_ / "s1_overlap"}); }),
              AllOf(HasSubstr("shares 1 view(s)"), HasSubstr("room_0/v000")));

  // A shard of another partition, and an unfinished shard.
  copy_tree(dir_ / "s1", dir_ / "s1_of_3");
  m = json::parse(read_file(dir_ / "s1_of_3/manifest.json"));
  m["shard"]["count"] = 3;
  write_file_atomic(dir_ / "s1_of_3/manifest.json", m.dump());
  EXPECT_THAT(error_of([&] { merge_shards(out, {dir_ / "s0", dir_ / "s1_of_3"}); }), HasSubstr("shard 1/3"));
  copy_tree(dir_ / "s1", dir_ / "s1_unfinished");
  fs::remove(dir_ / "s1_unfinished/manifest.json");
  EXPECT_THAT(error_of([&] { merge_shards(out, {dir_ / "s0", dir_ / "s1_unfinished"}); }),
              HasSubstr("has not finished"));
  EXPECT_FALSE(fs::exists(out / "manifest.json"));
}

TEST(Pipeline, SplitTimingMovesEveryWallClockField) {
  const json report = {{"settings", {{"spp", 4}, {"threads", 2}}},
                       {"counters", {{"rays", 10}, {"color_seconds", 0.5}, {"rays_per_second", 20.0}}},
                       {"probes", {{"seconds", {{"total", 1.0}}}, {"rays", 5}}},
                       {"timings", {{"total_seconds", 2.0}}}};
  json timing;
  const json kept = split_timing(report, &timing);
  EXPECT_EQ(kept, (json{{"settings", {{"spp", 4}}}, {"counters", {{"rays", 10}}}, {"probes", {{"rays", 5}}}}));
  EXPECT_EQ(timing["settings"]["threads"], 2);
  EXPECT_EQ(timing["counters"]["color_seconds"], 0.5);
  EXPECT_EQ(timing["probes"]["seconds"]["total"], 1.0);
  EXPECT_EQ(timing["timings"]["total_seconds"], 2.0);
}

}  // namespace
}  // namespace phyir::dataset
