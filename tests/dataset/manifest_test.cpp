// manifest.json: text -> parse -> text is byte-identical; scene records hash the glTF and
// every file it references; malformed manifests are refused with the file named; the
// difference describer names the first differing key.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "dataset_test_helpers.h"
#include "phyir/core/atomic_file.h"
#include "phyir/core/error.h"
#include "phyir/dataset/checksum.h"
#include "phyir/dataset/manifest.h"

namespace phyir::dataset {
namespace {

using ::testing::HasSubstr;
using nlohmann::json;

json tiny_settings_json() { return test::tiny_settings(2).to_json(); }

Manifest sample_manifest() {
  Manifest m;
  m.settings = tiny_settings_json();
  m.scenes_dir = "rooms";
  m.shard = {1, 3};
  m.scene_names = {"a", "b"};
  m.scenes = {json{{"name", "a"}, {"file", "a.gltf"}, {"split", "train"}, {"sha256", "00"}},
              json{{"name", "b"}, {"file", "b.gltf"}, {"split", "test"}, {"sha256", "11"}}};
  for (const char* scene : {"a", "b"})
    for (int k = 0; k < 2; ++k)
      m.views.push_back({{"id", view_id(scene, k, 2)},
                         {"scene", {{"name", scene}, {"file", std::string(scene) + ".gltf"}, {"sha256", "00"}}},
                         {"index", k},
                         {"split", scene == std::string("a") ? "train" : "test"},
                         {"dir", view_folder(scene, k, 2).generic_string()},
                         {"seed", view_seed(1, scene, k)},
                         {"viewpoint", {{"position", {0.5, 1.5, -0.25}}}},
                         {"files", {{{"path", "color.exr"}, {"size", 123}, {"sha256", "ab"}}}}});
  return m;
}

TEST(Manifest, RoundTripIsByteIdentical) {
  const Manifest m = sample_manifest();
  const std::string text = manifest_text(m);
  const Manifest back = parse_manifest(json::parse(text), "test");
  EXPECT_EQ(manifest_text(back), text);
  EXPECT_EQ(back.settings, m.settings);
  EXPECT_EQ(back.shard.index, 1);
  EXPECT_EQ(back.shard.count, 3);
  EXPECT_EQ(back.views, m.views);  // scene.path is added in the text and removed on parsing
  EXPECT_EQ(back.views_total(), 4u);
  // One line per view, with the scene's path.
  const json parsed = json::parse(text);
  EXPECT_EQ(parsed["views"][0]["scene"]["path"], "rooms/a.gltf");
  EXPECT_EQ(parsed["counts"]["views_per_split"]["train"], 2);
  EXPECT_EQ(parsed["counts"]["bytes"], 4 * 123);
  EXPECT_THAT(text, HasSubstr("\n    {\"dir\":\"views/a/v000\""));
}

TEST(Manifest, FileRoundTripAndMissingManifest) {
  const auto dir = test::fresh_test_dir();
  EXPECT_THROW(
      {
        try {
          read_manifest(dir);
        } catch (const Error& e) {
          EXPECT_THAT(e.what(), HasSubstr("has not finished"));
          throw;
        }
      },
      Error);
  const Manifest m = sample_manifest();
  write_manifest(dir, m);
  EXPECT_EQ(manifest_text(read_manifest(dir)), manifest_text(m));
}

TEST(Manifest, RefusesOtherFormats) {
  json j = json::parse(manifest_text(sample_manifest()));
  j["format"] = "something-else";
  EXPECT_THROW(parse_manifest(j, "x.json"), Error);
  j = json::parse(manifest_text(sample_manifest()));
  j["format_version"] = 99;
  EXPECT_THROW(parse_manifest(j, "x.json"), Error);
  j = json::parse(manifest_text(sample_manifest()));
  j["views"][1].erase("files");
  try {
    parse_manifest(j, "x.json");
    FAIL();
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("x.json"));
    EXPECT_THAT(e.what(), HasSubstr("files"));
  }
}

TEST(Manifest, SceneRecordHashesTheGltfAndItsFiles) {
  const auto dir = test::fresh_test_dir();
  const auto rooms = test::make_rooms(dir, 1, scenes::RoomPreset::Hard, 2);  // textured: .bin and PNGs
  const json r = scene_record(rooms, {"room_0", "room_0.gltf"}, "val", 3);
  EXPECT_EQ(r["sha256"], sha256_file(rooms / "room_0.gltf"));
  EXPECT_EQ(r["split"], "val");
  EXPECT_EQ(r["views"], 3);
  ASSERT_GE(r["dependencies"].size(), 2u);
  for (const json& d : r["dependencies"])
    EXPECT_EQ(d["sha256"], sha256_file(rooms / d["file"].get<std::string>()));
  // Changing a texture changes content_sha256 but not the glTF's sha256.
  const std::string texture = r["dependencies"].back()["file"];
  test::flip_byte(rooms / texture, 100);
  const json changed = scene_record(rooms, {"room_0", "room_0.gltf"}, "val", 3);
  EXPECT_EQ(changed["sha256"], r["sha256"]);
  EXPECT_NE(changed["content_sha256"], r["content_sha256"]);
}

// The environment map a scene declares (extras.phyir.environment) is a file the render reads:
// changing it must change content_sha256, so views rendered under the old sky are redone.
TEST(Manifest, SceneRecordCountsTheScenesEnvironmentMap) {
  const auto dir = test::fresh_test_dir();
  const auto rooms = test::make_rooms(dir, 1, scenes::RoomPreset::Mini, 2);
  write_file_atomic(rooms / "sky.exr", "stand-in bytes: only hashed here");
  json gltf = json::parse(read_file(rooms / "room_0.gltf"));
  gltf["scenes"][0]["extras"]["phyir"]["environment"] = {{"uri", "sky.exr"}, {"scale", 1.0}};
  write_file_atomic(rooms / "room_0.gltf", gltf.dump(2));
  const json r = scene_record(rooms, {"room_0", "room_0.gltf"}, "val", 3);
  bool listed = false;
  for (const json& d : r["dependencies"]) listed = listed || d["file"] == "sky.exr";
  EXPECT_TRUE(listed) << r["dependencies"].dump();
  write_file_atomic(rooms / "sky.exr", "another sky");
  EXPECT_NE(scene_record(rooms, {"room_0", "room_0.gltf"}, "val", 3)["content_sha256"], r["content_sha256"]);
}

// A scene's extras.attribution (furnished apartments) travels into its record, and the
// manifest credits every CC-BY model once, leaving public-domain ones out.
TEST(Manifest, CollectsTheAttributionsItsViewsNeed) {
  const auto dir = test::fresh_test_dir();
  const auto rooms = test::make_rooms(dir, 1, scenes::RoomPreset::Mini, 2);
  json gltf = json::parse(read_file(rooms / "room_0.gltf"));
  const json by = {{"name", "Sofa"}, {"id", "Scopia#sofa"}, {"library", "Scopia"}, {"creator", "eTeks"},
                   {"licence", "Creative Commons Attribution 3.0 Unported license"}};
  const json cc0 = {{"name", "Comb"}, {"id", "Blend Swap CC-0#comb"}, {"library", "Blend Swap CC-0"},
                    {"creator", "JonFreer"}, {"licence", "Public domain"}};
  gltf["scenes"][0]["extras"]["attribution"] = json::array({by, cc0});
  write_file_atomic(rooms / "room_0.gltf", gltf.dump(2));
  const json r = scene_record(rooms, {"room_0", "room_0.gltf"}, "train", 1);
  ASSERT_EQ(r["attribution"].size(), 2u);
  Manifest m = sample_manifest();
  m.scenes = {r, r};  // the same model in two scenes is credited once
  const json text = json::parse(manifest_text(m));
  ASSERT_TRUE(text.contains("attribution"));
  ASSERT_EQ(text["attribution"].size(), 1u);
  EXPECT_EQ(text["attribution"][0]["id"], "Scopia#sofa");
  EXPECT_FALSE(json::parse(manifest_text(sample_manifest())).contains("attribution"));  // rooms credit nobody
}

TEST(Manifest, DescribeDifferenceNamesTheKey) {
  const json a = {{"render", {{"spp", 4}, {"width", 64}}}};
  json b = a;
  EXPECT_EQ(describe_difference(a, b, "settings"), "");
  b["render"]["spp"] = 8;
  EXPECT_EQ(describe_difference(a, b, "settings"), "settings.render.spp: 4 vs 8");
}

}  // namespace
}  // namespace phyir::dataset
