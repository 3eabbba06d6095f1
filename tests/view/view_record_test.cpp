// The view folder's records: view.json's input exposure, folders without a record, the
// manifest's views and the scan for view folders.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "phyir/core/error.h"
#include "phyir/view/input_exposure.h"
#include "phyir/view/view_files.h"
#include "phyir/view/view_record.h"

namespace fs = std::filesystem;
namespace pv = phyir::view;

namespace {

fs::path scratch(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("phyir_view_test_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

void touch(const fs::path& file) {
  fs::create_directories(file.parent_path());
  std::ofstream(file) << "x";
}

}  // namespace

TEST(InputExposure, RoundTripsThroughItsJson) {
  pv::InputExposure e;
  e.stops = -1.25;
  e.base_stops = -1.0;
  e.jitter_stops = -0.25;
  e.percentile_value = 3.5;
  e.view = "Raw";
  const pv::InputExposure back = pv::InputExposure::from_json(e.to_json(), "test");
  EXPECT_TRUE(back.recorded);
  EXPECT_EQ(back.stops, e.stops);
  EXPECT_EQ(back.base_stops, e.base_stops);
  EXPECT_EQ(back.jitter_stops, e.jitter_stops);
  EXPECT_EQ(back.percentile_value, e.percentile_value);
  EXPECT_TRUE(back.raw_view());
  EXPECT_EQ(e.to_json().at("file"), pv::kInputFile);
  // Fixed exposure: no percentile in the record.
  e.percentile_value.reset();
  EXPECT_FALSE(e.to_json().contains("percentile_value"));
}

TEST(ViewRecord, ReadsTheExposureFromViewJson) {
  const fs::path dir = scratch("view_json");
  EXPECT_FALSE(pv::read_view(dir).input.recorded);  // no view.json: 0 stops, not recorded
  EXPECT_EQ(pv::read_view(dir).input.factor(), 1.0);
  EXPECT_EQ(pv::read_view(dir).id, dir.filename().string());  // no record: named after its folder
  std::ofstream(dir / pv::kViewRecordFile) << R"({"id": "a/v0", "input": {"exposure_stops": -1.5, "view": "Standard"}})";
  const pv::ViewRecord v = pv::read_view(dir);
  EXPECT_EQ(v.id, "a/v0");
  EXPECT_EQ(v.dir, dir);
  EXPECT_TRUE(v.input.recorded);
  EXPECT_EQ(v.input.stops, -1.5);
  EXPECT_DOUBLE_EQ(v.input.factor(), std::exp2(-1.5));
  EXPECT_FALSE(v.input.raw_view());
  std::ofstream(dir / pv::kViewRecordFile) << R"({"input": {"exposure_stops": "bright"}})";
  EXPECT_THROW(pv::read_view(dir), phyir::Error);
  std::ofstream(dir / pv::kViewRecordFile) << "{not json";
  EXPECT_THROW(pv::read_view(dir), phyir::Error);
}

TEST(ViewRecord, ParsesTheTypedFields) {
  const nlohmann::json record = {{"id", "room_0/v003"},
                                 {"scene", {{"name", "room_0"}}},
                                 {"split", "val"},
                                 {"dir", "views/room_0/v003"},
                                 {"index", 3},
                                 {"seed", 1234567890123ull},
                                 {"viewpoint", {{"position", {1.0, 1.5, -2.0}}}},
                                 {"input", {{"exposure_stops", 0.5}}}};
  const pv::ViewRecord v = pv::parse_view_record(record, "/data", "m.json");
  EXPECT_EQ(v.id, "room_0/v003");
  EXPECT_EQ(v.scene, "room_0");
  EXPECT_EQ(v.split, "val");
  EXPECT_EQ(v.dir, fs::path("/data/views/room_0/v003"));
  EXPECT_EQ(v.index, 3);
  EXPECT_EQ(v.seed, 1234567890123ull);
  ASSERT_TRUE(v.camera.has_value());
  EXPECT_EQ(v.camera->z, -2.0f);
  EXPECT_EQ(v.input.stops, 0.5);
  EXPECT_EQ(v.json, record);
  try {
    pv::parse_view_record({{"id", 7}}, "/data", "m.json");
    FAIL() << "a mistyped id was accepted";
  } catch (const phyir::Error& e) {
    EXPECT_NE(std::string(e.what()).find("m.json"), std::string::npos) << e.what();
  }
}

TEST(ViewRecord, ManifestSplitsAndDeepFolders) {
  // A dataset's views live three levels down (views/<scene>/<vNNN>); without a manifest they
  // are found by scanning, interrupted writes (.tmp-*) skipped.
  const fs::path root = scratch("manifest");
  touch(root / "views" / "s" / "v000" / pv::kColorFile);
  touch(root / "views" / "s" / "v001" / pv::kInputFile);
  touch(root / "views" / "s" / ".tmp-v002" / pv::kColorFile);
  EXPECT_EQ(pv::find_views(root).size(), 2u);
  EXPECT_EQ(pv::find_views(root / "views" / "s" / "v000").size(), 1u);  // a view folder itself
  std::ofstream(root / pv::kManifestFile) << R"({"format": "phyir-dataset", "format_version": 1, "views": [
      {"id": "s/v000", "dir": "views/s/v000", "split": "train"},
      {"id": "s/v001", "dir": "views/s/v001", "split": "val", "input": {"exposure_stops": 2}}]})";
  const auto train = pv::find_views(root, "train");
  ASSERT_EQ(train.size(), 1u);
  EXPECT_EQ(train[0].dir, root / "views" / "s" / "v000");
  EXPECT_FALSE(train[0].input.recorded);
  const auto all = pv::find_views(root, "");
  ASSERT_EQ(all.size(), 2u);
  EXPECT_EQ(all[1].input.stops, 2.0);
  EXPECT_THROW(pv::find_views(root, "test"), phyir::Error);
}

TEST(ViewRecord, ManifestErrorsNameTheFile) {
  const fs::path root = scratch("bad_manifest");
  const auto message = [&] {
    try {
      pv::read_manifest_views(root);
    } catch (const phyir::Error& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(message().find("not finished"), std::string::npos);  // missing: the run has not finished
  std::ofstream(root / pv::kManifestFile) << "{";
  EXPECT_NE(message().find("not valid JSON"), std::string::npos);
  std::ofstream(root / pv::kManifestFile) << R"({"format": "other"})";
  EXPECT_NE(message().find("not a phyir dataset manifest"), std::string::npos);
  std::ofstream(root / pv::kManifestFile) << R"({"format": "phyir-dataset", "format_version": 1, "views": [{"id": "a"}]})";
  EXPECT_NE(message().find("without \"dir\""), std::string::npos);
}
