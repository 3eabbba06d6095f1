// AssetLibrary on the fixture libraries of tests/data/assets (scripts/assets/
// make_fixture_library.py): catalogs, lookups, licences, and the errors that name the
// archive and the problem.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "gltf_test_helpers.h"
#include "phyir/core/error.h"
#include "phyir/scenes/asset_library.h"

namespace phyir::scenes {
namespace {

namespace fs = std::filesystem;

const fs::path kAssets = fs::path(PHYIR_TEST_DATA_DIR) / "assets";
const fs::path kFixture = kAssets / "fixture" / "PhyirFixture.sh3f";

std::string open_error(const fs::path& path) {
  try {
    AssetLibrary::open(path);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(AssetLibrary, OpensTheFixtureFolderAndFile) {
  const AssetLibrary from_folder = AssetLibrary::open(kAssets / "fixture");
  const AssetLibrary from_file = AssetLibrary::open(kFixture);
  ASSERT_EQ(from_folder.entries().size(), 5u);
  EXPECT_EQ(from_file.entries().size(), 5u);
  ASSERT_EQ(from_folder.archives().size(), 1u);
  const AssetArchive& archive = from_folder.archives()[0];
  EXPECT_EQ(archive.name, "PhyIR fixture");
  EXPECT_EQ(archive.licence, "Public domain (CC0 1.0)");
  EXPECT_NE(archive.licence_text.find("CC0"), std::string::npos);  // LICENSE.TXT
  EXPECT_EQ(archive.entry_count, 5u);
  for (const AssetEntry& e : from_folder.entries()) {
    EXPECT_EQ(e.archive, kAssets / "fixture" / "PhyirFixture.sh3f");
    EXPECT_EQ(e.licence, "Public domain (CC0 1.0)");
    EXPECT_EQ(e.creator, "Fixture Maker");
  }
}

TEST(AssetLibrary, LooksUpByIdAndCategory) {
  const AssetLibrary library = AssetLibrary::open(kFixture);
  ASSERT_NE(library.find("PhyIR#lamp"), nullptr);
  EXPECT_EQ(library.find("PhyIR#lamp")->name, "Lamp");
  EXPECT_EQ(library.find("PhyIR#sofa"), nullptr);
  EXPECT_EQ(library.at("PhyIR#table").name, "Table \xc3\xa9l\xc3\xa9gante");
  EXPECT_EQ(library.at("PhyIR#chair").name, "Chaise d\xc3\xa9" "cor\xc3\xa9" "e");  // raw Latin-1 bytes
  EXPECT_THROW(library.at("PhyIR#sofa"), Error);
  const auto lights = library.in_category("Lights");
  ASSERT_EQ(lights.size(), 1u);
  EXPECT_EQ(lights[0]->light_sources.size(), 2u);
  EXPECT_TRUE(library.in_category("lights").empty());  // exact names
  const auto counts = library.category_counts();
  EXPECT_EQ(counts.size(), 5u);
  EXPECT_EQ(counts.at("Doors and windows"), 1u);
}

TEST(AssetLibrary, FixtureCatalogValues) {
  const AssetLibrary library = AssetLibrary::open(kFixture);
  const AssetEntry& table = library.at("PhyIR#table");
  EXPECT_EQ(table.tags, (std::vector<std::string>{"Wood", "Dining", "Table"}));
  EXPECT_EQ(table.description, "Ratio 3:2, key=value");
  EXPECT_NEAR(table.drop_on_top_elevation, 74.0f / 75.0f, 1e-6f);
  EXPECT_EQ(library.at("PhyIR#chair").tags, (std::vector<std::string>{"Seat", "Chair"}));  // continued line
  const AssetEntry& window = library.at("PhyIR#window");
  EXPECT_TRUE(window.is_door_or_window);
  EXPECT_FALSE(window.movable);
  EXPECT_EQ(window.opening.kind, OpeningKind::Window);
  EXPECT_NEAR(window.elevation_m, 0.9f, 1e-6f);
  EXPECT_NEAR(window.opening.wall_thickness_m, 0.08f, 1e-6f);
  EXPECT_NEAR(window.opening.wall_distance_m, 0.01f, 1e-6f);
  EXPECT_EQ(window.opening.sashes.size(), 2u);
  EXPECT_LT(library.at("PhyIR#plant").drop_on_top_elevation, 0.0f);  // nothing goes on a plant
}

TEST(AssetLibrary, RepeatedIdsKeepTheFirst) {
  const AssetLibrary library = AssetLibrary::open(std::vector<fs::path>{kFixture, kFixture});
  EXPECT_EQ(library.entries().size(), 5u);
  EXPECT_EQ(library.duplicate_ids().size(), 5u);
  EXPECT_EQ(library.archives().size(), 2u);
}

TEST(AssetLibrary, ErrorsNameTheArchiveAndTheProblem) {
  const fs::path broken = kAssets / "broken";
  EXPECT_EQ(open_error(broken / "no_catalog.sh3f"),
            (broken / "no_catalog.sh3f").string() +
                ": no PluginFurnitureCatalog.properties in this archive: not a Sweet Home 3D furniture library");
  EXPECT_EQ(open_error(broken / "missing_model.sh3f"),
            (broken / "missing_model.sh3f").string() +
                ": model#2=/ghost/ghost.obj (entry 'Broken#ghost'): no such file in the archive");
  EXPECT_EQ(open_error(broken / "bad_number.sh3f"),
            (broken / "bad_number.sh3f").string() + ": width#2=abc is not a number (line 16)");
  EXPECT_EQ(open_error(kAssets / "absent"), (kAssets / "absent").string() + ": no such folder or .sh3f file");
  EXPECT_EQ(open_error(kAssets), kAssets.string() + ": no .sh3f furniture library in this folder");
}

TEST(AssetLibrary, CorruptArchivesAreRefusedNamingTheFile) {
  const fs::path dir = test::fresh_test_dir();
  std::ifstream in(kFixture, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  // Cut before the central directory: not a zip any more.
  const fs::path truncated = dir / "truncated.sh3f";
  test::write_bytes(truncated, bytes.data(), bytes.size() / 2);
  const std::string truncated_error = open_error(truncated);
  EXPECT_EQ(truncated_error.rfind(truncated.string() + ": cannot open as a zip archive: ", 0), 0u) << truncated_error;
  const fs::path text = dir / "text.sh3f";
  test::write_bytes(text, "not a zip", 9);
  EXPECT_NE(open_error(text).find("text.sh3f: cannot open as a zip archive"), std::string::npos);
  // Damage the compressed catalog (its bytes follow its local header): a CRC or inflate error.
  std::string damaged = bytes;
  const size_t catalog = damaged.find("PluginFurnitureCatalog.properties") + 33;
  for (size_t i = catalog + 20; i < catalog + 60; ++i) damaged[i] = static_cast<char>(damaged[i] ^ 0x5A);
  const fs::path corrupt = dir / "corrupt.sh3f";
  test::write_bytes(corrupt, damaged.data(), damaged.size());
  const std::string corrupt_error = open_error(corrupt);
  EXPECT_NE(corrupt_error.find("corrupt.sh3f: 'PluginFurnitureCatalog.properties': "), std::string::npos) << corrupt_error;
}

}  // namespace
}  // namespace phyir::scenes
