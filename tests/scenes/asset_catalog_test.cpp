// The furniture catalog parser (PluginFurnitureCatalog.properties -> AssetEntry) on
// hand-written catalogs: Java properties syntax, units, light sources, doors and windows,
// and errors that name the archive, the key, its value and the line.
#include <gtest/gtest.h>

#include <string>

#include "phyir/core/error.h"
#include "phyir/scenes/asset_library.h"

namespace phyir::scenes {
namespace {

// The keys every entry needs, for entry `n`, in the catalog's syntax.
std::string minimal_entry(int n, const std::string& extra = "") {
  const std::string i = std::to_string(n);
  return "id#" + i + "=Test#e" + i + "\nname#" + i + "=Entry " + i + "\ncategory#" + i + "=Kitchen\nmodel#" + i +
         "=/m/e" + i + ".obj\nwidth#" + i + "=100\ndepth#" + i + "=50\nheight#" + i + "=80\n" + extra;
}

// The message of the phyir::Error `parse` throws ("" when it does not throw).
std::string error_of(const std::string& catalog) {
  try {
    parse_furniture_catalog(catalog, "test.sh3f");
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(AssetCatalog, ReadsJavaPropertiesSyntax) {
  // \uXXXX and a raw Latin-1 byte (0xE9), "\:" and "\=", ':' and ' ' separators, '!'
  // comments, a continued line, CRLF line ends.
  const std::string catalog =
      "! comment\r\nname=Lib\r\nlicense=CC0\r\n"
      "id#1=Test#a\r\nname#1=Caf\\u00e9 \xe9t\\u00E9\r\ncategory#1 Living room\r\n"
      "description#1 : ratio 3\\:2, a\\=b\r\ntags#1=One, \\\r\n    Two ,Three\r\n"
      "model#1=/m/a.obj\r\nwidth#1=10\r\ndepth#1=20\r\nheight#1=30\r\n";
  const std::vector<AssetEntry> entries = parse_furniture_catalog(catalog, "test.sh3f");
  ASSERT_EQ(entries.size(), 1u);
  const AssetEntry& e = entries[0];
  EXPECT_EQ(e.name, "Caf\xc3\xa9 \xc3\xa9t\xc3\xa9");  // UTF-8
  EXPECT_EQ(e.category, "Living room");
  EXPECT_EQ(e.description, "ratio 3:2, a=b");
  EXPECT_EQ(e.tags, (std::vector<std::string>{"One", "Two", "Three"}));
  EXPECT_EQ(e.library, "Lib");
  EXPECT_EQ(e.licence, "CC0");
  EXPECT_EQ(e.model_path, "m/a.obj");  // the leading '/' is the archive's root
}

TEST(AssetCatalog, ConvertsUnitsAndDefaults) {
  const std::vector<AssetEntry> entries = parse_furniture_catalog(
      "name=Lib\n" + minimal_entry(1, "elevation#1=75\ndropOnTopElevation#1=60\nmovable#1=false\n") + minimal_entry(2),
      "test.sh3f");
  ASSERT_EQ(entries.size(), 2u);
  EXPECT_NEAR(entries[0].size_m.x, 1.0f, 1e-6f);   // width
  EXPECT_NEAR(entries[0].size_m.y, 0.8f, 1e-6f);   // height
  EXPECT_NEAR(entries[0].size_m.z, 0.5f, 1e-6f);   // depth
  EXPECT_NEAR(entries[0].elevation_m, 0.75f, 1e-6f);
  EXPECT_NEAR(entries[0].drop_on_top_elevation, 0.75f, 1e-6f);  // 60 of 80 cm
  EXPECT_FALSE(entries[0].movable);
  EXPECT_FLOAT_EQ(entries[1].drop_on_top_elevation, 1.0f);  // default: on top
  EXPECT_TRUE(entries[1].movable);
  EXPECT_FALSE(entries[1].is_door_or_window);
  EXPECT_EQ(entries[1].model_rotation, glm::mat3(1.0f));
}

TEST(AssetCatalog, ModelRotationIsRowMajor) {
  const std::vector<AssetEntry> entries =
      parse_furniture_catalog(minimal_entry(1, "modelRotation#1=1 0 0 0 0 1 0 -1 0\n"), "test.sh3f");
  const glm::mat3& r = entries[0].model_rotation;
  // Rows (1 0 0), (0 0 1), (0 -1 0): OBJ +Z (up in a Z-up file) becomes +Y.
  EXPECT_EQ(r * glm::vec3(0, 0, 1), glm::vec3(0, 1, 0));
  EXPECT_EQ(r * glm::vec3(0, 1, 0), glm::vec3(0, 0, -1));
}

TEST(AssetCatalog, ReadsSeveralLightSources) {
  // Two sources in a 100 x 80 (height) x 50 cm lamp; Y counts from the front in plan.
  const std::vector<AssetEntry> entries = parse_furniture_catalog(
      minimal_entry(1, "lightSourceX#1=50 25\nlightSourceY#1=10 40\nlightSourceZ#1=80 40\n"
                       "lightSourceColor#1=#FF8000 255\nlightSourceDiameter#1=5 10\n"),
      "test.sh3f");
  const AssetEntry& lamp = entries[0];
  ASSERT_TRUE(lamp.is_light());
  ASSERT_EQ(lamp.light_sources.size(), 2u);
  const AssetLightSource& a = lamp.light_sources[0];
  EXPECT_NEAR(a.relative_position.x, 0.5f, 1e-6f);
  EXPECT_NEAR(a.relative_position.y, 1.0f, 1e-6f);
  EXPECT_NEAR(a.relative_position.z, 0.8f, 1e-6f);  // 10 cm behind the front of 50
  EXPECT_EQ(a.colour, glm::vec3(1.0f, 128.0f / 255.0f, 0.0f));
  EXPECT_NEAR(a.diameter_m, 0.05f, 1e-7f);
  // Position in the model frame: x centred, y up from the bottom, +z towards the front.
  const glm::vec3 p = a.position(lamp.size_m);
  EXPECT_NEAR(p.x, 0.0f, 1e-6f);
  EXPECT_NEAR(p.y, 0.8f, 1e-6f);
  EXPECT_NEAR(p.z, 0.15f, 1e-6f);
  const AssetLightSource& b = lamp.light_sources[1];
  EXPECT_EQ(b.colour, glm::vec3(0.0f, 0.0f, 1.0f));  // decimal 255 = 0x0000FF
  EXPECT_NEAR(b.position(lamp.size_m).z, -0.15f, 1e-6f);
}

TEST(AssetCatalog, ReadsDoorsAndWindows) {
  const std::vector<AssetEntry> entries = parse_furniture_catalog(
      minimal_entry(1, "doorOrWindow#1=true\nname#1=Front door\ndoorOrWindowWallThickness#1=20\n"
                       "doorOrWindowWallDistance#1=5\ndoorOrWindowCutOutShape#1=M0,0 v1 h1 v-1 z\n"
                       "doorOrWindowSashXAxis#1=10\ndoorOrWindowSashYAxis#1=40\ndoorOrWindowSashWidth#1=80\n"
                       "doorOrWindowSashStartAngle#1=0\ndoorOrWindowSashEndAngle#1=90\n"
                       "lightSourceX#1=1\n") +
          minimal_entry(2, "doorOrWindow#2=true\nelevation#2=100\n") +
          minimal_entry(3, "doorOrWindow#3=true\n") +
          minimal_entry(4, "doorOrWindow#4=true\nname#4=French window\n"),
      "test.sh3f");
  const AssetEntry& door = entries[0];
  ASSERT_TRUE(door.is_door_or_window);
  EXPECT_EQ(door.opening.kind, OpeningKind::Door);
  EXPECT_NEAR(door.opening.wall_thickness_m, 0.20f, 1e-6f);
  EXPECT_NEAR(door.opening.wall_distance_m, 0.05f, 1e-6f);
  EXPECT_EQ(door.opening.cut_out_shape, "M0,0 v1 h1 v-1 z");
  ASSERT_EQ(door.opening.sashes.size(), 1u);
  EXPECT_NEAR(door.opening.sashes[0].axis_x_m, 0.1f, 1e-6f);
  EXPECT_NEAR(door.opening.sashes[0].axis_z_m, 0.4f, 1e-6f);
  EXPECT_NEAR(door.opening.sashes[0].width_m, 0.8f, 1e-6f);
  EXPECT_NEAR(door.opening.sashes[0].end_angle, 1.5707963f, 1e-6f);
  EXPECT_FALSE(door.is_light());  // Sweet Home 3D reads no light source on an opening
  EXPECT_EQ(entries[1].opening.kind, OpeningKind::Window);  // unnamed, 1 m up
  EXPECT_EQ(entries[2].opening.kind, OpeningKind::Door);    // unnamed, on the floor
  EXPECT_NEAR(entries[2].opening.wall_thickness_m, 0.5f, 1e-6f);  // default: its depth
  EXPECT_EQ(entries[3].opening.kind, OpeningKind::Window);  // the name wins over elevation 0
}

TEST(AssetCatalog, ReadsEntriesPastAGapAndNamesMissingIds) {
  const std::vector<AssetEntry> entries =
      parse_furniture_catalog("name=Lib\n" + minimal_entry(1) + minimal_entry(3), "test.sh3f");
  ASSERT_EQ(entries.size(), 2u);
  EXPECT_EQ(entries[1].index, 3);
  std::string without_id = minimal_entry(1);
  without_id.erase(0, without_id.find('\n') + 1);
  EXPECT_EQ(parse_furniture_catalog("name=Lib\n" + without_id, "test.sh3f")[0].id, "Lib#1");
}

TEST(AssetCatalog, BadValuesNameArchiveKeyValueAndLine) {
  std::string bad = minimal_entry(12);
  bad.replace(bad.find("width#12=100"), 12, "width#12=abc");
  EXPECT_EQ(error_of(bad), "test.sh3f: width#12=abc is not a number (line 5)");
  EXPECT_NE(error_of(minimal_entry(1, "elevation#1=1,5\n")).find("elevation#1=1,5 is not a number"), std::string::npos);
  EXPECT_NE(error_of(minimal_entry(1, "movable#1=yes\n")).find("movable#1=yes is not true or false"), std::string::npos);
  std::string negative = minimal_entry(1);
  negative.replace(negative.find("height#1=80"), 11, "height#1=-3");
  EXPECT_NE(error_of(negative).find("height#1=-3 must be a length > 0 cm"), std::string::npos);
  std::string no_model = minimal_entry(1);
  no_model.erase(no_model.find("model#1"), no_model.find('\n', no_model.find("model#1")) - no_model.find("model#1") + 1);
  EXPECT_EQ(error_of(no_model), "test.sh3f: model#1 is required but missing or empty");
}

TEST(AssetCatalog, ListLengthsMustAgree) {
  EXPECT_NE(error_of(minimal_entry(1, "lightSourceX#1=1 2\nlightSourceY#1=1\nlightSourceZ#1=1 2\n"
                                      "lightSourceColor#1=#FFFFFF #FFFFFF\n"))
                .find("lightSourceY#1=1 has 1 numbers, expected 2"),
            std::string::npos);
  EXPECT_NE(error_of(minimal_entry(1, "lightSourceX#1=1\nlightSourceY#1=1\nlightSourceZ#1=1\n"
                                      "lightSourceColor#1=#GGGGGG\n"))
                .find("'#GGGGGG', not a colour"),
            std::string::npos);
  EXPECT_NE(error_of(minimal_entry(1, "modelRotation#1=1 0 0 0 1 0 0 0\n")).find("has 8 numbers, expected 9"),
            std::string::npos);
  EXPECT_NE(error_of(minimal_entry(1, "lightSourceX#1=1\n")).find("lightSourceY#1 is required but missing"),
            std::string::npos);
}

TEST(AssetCatalog, RefusesCatalogsWithoutFurnitureAndBadEscapes) {
  EXPECT_EQ(error_of("name=Lib\n"), "test.sh3f: PluginFurnitureCatalog.properties has no furniture (no name#N keys)");
  EXPECT_NE(error_of("name#1=bad \\u12G4\n").find("line 1: malformed \\uXXXX escape"), std::string::npos);
}

}  // namespace
}  // namespace phyir::scenes
