// The glTF schema check (scenes/src/gltf/schema/gltf_schema.h; docs/robustness.md, "Schema validation"):
// a valid file with every object type loads; each mutation of it breaking one rule is
// refused with a message naming the object, the value and the rule; valid corner cases
// load; and the Khronos validator's verdict on every file is the one recorded (skipped
// when node and npm, or the validator package, are not available).
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "gltf_schema_mutations.h"
#include "gltf_test_helpers.h"
#include "phyir/core/error.h"
#include "phyir/scenes/gltf_loader.h"

namespace phyir::scenes {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using test::Edit;
using test::erase;
using test::Mutation;
using test::set;
using test::Validator;

const fs::path kQuadData = fs::path(PHYIR_TEST_DATA_DIR) / "gltf";

// A fresh folder holding textured_quad's .bin and texture, which the documents refer to.
fs::path folder_with_quad_data() {
  const fs::path dir = test::fresh_test_dir();
  fs::copy_file(kQuadData / "textured_quad.bin", dir / "textured_quad.bin");
  fs::copy(kQuadData / "textures", dir / "textures", fs::copy_options::recursive);
  return dir;
}

fs::path write_document(const fs::path& dir, const std::string& name, const json& doc) {
  const fs::path path = dir / (name + ".gltf");
  std::ofstream(path) << doc.dump(1);
  return path;
}

json edited(const Edit& edit) {
  json doc = test::schema_base_document();
  edit(doc);
  return doc;
}

// The phyir::Error message of loading `path`, or "" when it loads.
std::string load_error(const fs::path& path) {
  try {
    load_gltf(path);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

// Valid files the schema check must let through, each near a rule it checks.
std::map<std::string, Edit> valid_corner_cases() {
  const std::string light = "/extensions/KHR_lights_punctual/lights/";
  return {
      {"ior_zero", set("/materials/0/extensions/KHR_materials_ior/ior", 0)},  // oneOf: exactly 0, or >= 1
      {"range_on_a_directional_light", set(light + "0/type", "directional")},
      {"spot_cone_limits",
       set(light + "1/spot", {{"innerConeAngle", 0}, {"outerConeAngle", 1.5707963267948966}})},
      {"rotation_at_its_bounds", set("/nodes/2/rotation", {0, 0, 1, 0})},
      {"orthographic_xmag_negative", set("/cameras/1/orthographic/xmag", -1)},  // spec: SHOULD NOT
      {"alpha_cutoff_without_alpha_mode", erase("/materials/0/alphaMode")},
      {"perspective_without_zfar_and_aspect",
       test::all({erase("/cameras/0/perspective/zfar"), erase("/cameras/0/perspective/aspectRatio")})},
      {"unknown_properties_and_extras", test::all({set("/nodes/0/color", "red"), set("/nodes/0/extras", 5),
                                                   set("/accessors/0/extras", {1, 2})})},
      {"required_extension_also_used", set("/extensionsRequired", {"KHR_texture_transform"})},
      {"zfar_1e300", set("/cameras/0/perspective/zfar", 1e300)},
  };
}

// The first part of a rule, "accessor" of "accessor.sparse.count": the object type.
std::string object_type_of(const std::string& message) {
  static const std::regex rule(R"(, ([A-Za-z]+)[.\w]*\)$)");
  std::smatch match;
  return std::regex_search(message, match, rule) ? match[1].str() : "";
}

TEST(GltfSchema, BaseDocumentLoads) {
  const Scene scene =
      load_gltf(write_document(folder_with_quad_data(), "base", test::schema_base_document()));
  EXPECT_EQ(scene.meshes.size(), 1u);
  EXPECT_EQ(scene.cameras.size(), 2u);
}

TEST(GltfSchema, EveryMutationIsRefusedNamingObjectValueAndRule) {
  const fs::path dir = folder_with_quad_data();
  const std::vector<Mutation> mutations = test::schema_mutations();
  std::set<std::string> names, object_types;
  for (const Mutation& m : mutations) {
    SCOPED_TRACE(m.name);
    EXPECT_TRUE(names.insert(m.name).second) << "two mutations named " << m.name;
    const fs::path path = write_document(dir, m.name, edited(m.edit));
    EXPECT_EQ(load_error(path), path.string() + ": " + m.message);
    object_types.insert(object_type_of(m.message));
  }
  EXPECT_GE(mutations.size(), 40u);
  for (const char* type :
       {"glTF", "asset", "scene", "node", "mesh", "accessor", "buffer", "bufferView", "camera", "image",
        "texture", "sampler", "material", "textureInfo", "skin", "animation", "extension", "light"})
    EXPECT_EQ(object_types.count(type), 1u) << "no mutation breaks a rule of " << type;
  std::printf("[schema] %zu mutations refused, rules of %zu object types\n", mutations.size(),
              object_types.size());
}

TEST(GltfSchema, ValidCornerCasesLoad) {
  const fs::path dir = folder_with_quad_data();
  for (const auto& [name, edit] : valid_corner_cases()) {
    SCOPED_TRACE(name);
    EXPECT_EQ(load_error(write_document(dir, name, edited(edit))), "");
  }
}

// Errors the validator reports per file ("could not read the file" counts as one).
std::map<std::string, int> validator_errors(const std::string& output) {
  std::map<std::string, int> errors;
  static const std::regex counts(R"(^(.+\.gltf): (\d+) errors,)"),
      unreadable(R"(^(.+\.gltf): validator could not)");
  std::istringstream lines(output);
  for (std::string line; std::getline(lines, line);) {
    std::smatch match;
    if (std::regex_search(line, match, counts)) errors[match[1]] = std::stoi(match[2]);
    if (std::regex_search(line, match, unreadable)) errors[match[1]] = 1;
  }
  return errors;
}

std::string read_text(const fs::path& path) {
  std::ifstream in(path);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

TEST(GltfSchema, KhronosValidatorAgreesWithEveryVerdict) {
  if (std::system("command -v node >/dev/null 2>&1 && command -v npm >/dev/null 2>&1") != 0)
    GTEST_SKIP() << "node and npm are needed for the Khronos glTF validator";
  const fs::path dir = folder_with_quad_data();
  std::map<std::string, bool> expect_error;  // file -> the validator must report an error
  std::string files = " " + write_document(dir, "base", test::schema_base_document()).string();
  expect_error[(dir / "base.gltf").string()] = false;
  for (const auto& [name, edit] : valid_corner_cases()) {
    files += " " + write_document(dir, name, edited(edit)).string();
    expect_error[(dir / (name + ".gltf")).string()] = false;
  }
  const std::vector<Mutation> mutations = test::schema_mutations();
  for (const Mutation& m : mutations) {
    files += " " + write_document(dir, m.name, edited(m.edit)).string();
    expect_error[(dir / (m.name + ".gltf")).string()] = m.validator == Validator::kError;
  }
  const fs::path out = dir / "validator.txt", err = dir / "validator.err";
  const std::string script = std::string(PHYIR_SOURCE_ROOT) + "/scripts/gltf_validate.sh";
  const int status = std::system(
      ("bash " + script + " --quiet" + files + " >" + out.string() + " 2>" + err.string()).c_str());
  if (!WIFEXITED(status) || WEXITSTATUS(status) == 2)
    GTEST_SKIP() << "the validator could not be installed or run: " << read_text(err);

  const std::map<std::string, int> errors = validator_errors(read_text(out));
  for (const auto& [file, must_fail] : expect_error) {
    SCOPED_TRACE(file);
    ASSERT_EQ(errors.count(file), 1u) << "no verdict in " << out;
    EXPECT_EQ(errors.at(file) > 0, must_fail) << errors.at(file) << " errors";
  }
  std::map<Validator, int> verdicts;
  for (const Mutation& m : mutations) ++verdicts[m.validator];
  std::printf(
      "[schema] validator: %d mutations are errors, %d only warnings (enums), %d in extensions it does not "
      "know, %d valid (refused as a loader limitation); %zu valid files have no error\n",
      verdicts[Validator::kError], verdicts[Validator::kOnlyWarns],
      verdicts[Validator::kDoesNotKnowTheExtension], verdicts[Validator::kAccepts],
      expect_error.size() - mutations.size());
}

}  // namespace
}  // namespace phyir::scenes
