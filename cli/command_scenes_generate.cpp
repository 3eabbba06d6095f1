// phyir scenes generate: procedural indoor rooms, or furnished apartments from a furniture
// library, as glTF 2.0, plus a rooms.json summary.
#include <nlohmann/json.hpp>

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>

#include "commands.h"
#include "phyir/core/atomic_file.h"
#include "phyir/core/error.h"
#include "phyir/core/log.h"
#include "phyir/core/progress.h"
#include "phyir/scenes/apartment_generator.h"
#include "phyir/scenes/room_generator.h"

namespace phyir::cli {

namespace {

struct GenerateOptions {
  std::string out;
  int count = 1;
  uint64_t seed = 1;
  std::string preset = "mini";
  std::string assets = scenes::kDefaultAssetDir.string();  // apartments only
  std::string lighting = "mixed";                          // apartments only: day, night or mixed
  int rooms = 0;                                           // apartments only: 0 = from the seed
  bool portals = false;                                    // apartments only: windows as light portals
};

nlohmann::json to_json(const scenes::RoomSummary& s, int index) {
  return {{"file", s.file},
          {"index", index},
          {"meshes", s.meshes},
          {"triangles", s.triangles},
          {"materials", s.materials},
          {"textures", s.textures},
          {"cameras", s.cameras},
          {"emissive_meshes", s.emissive_meshes},
          {"candidate_viewpoints", s.candidate_viewpoints},
          {"material_kinds", s.material_kinds}};
}

nlohmann::json to_json(const scenes::ApartmentSummary& s, int index) {
  nlohmann::json j = to_json(s.files, index);
  j["rooms"] = s.rooms;
  j["lighting"] = scenes::apartment_lighting_name(s.lighting);
  j["pieces"] = s.pieces;
  j["lamps_lit"] = s.lamps_lit;
  j["punctual_lights"] = s.punctual_lights;
  j["attribution"] = s.attributions;
  j["missing_roles"] = s.missing_roles;
  return j;
}

scenes::AssetLibrary open_furniture_library(const std::filesystem::path& dir) {
  if (!std::filesystem::exists(dir))
    fail("--preset apartment needs a furniture library: {} does not exist. Install the Debian package "
         "sweethome3d-furniture (scripts/install_deps.sh does) or pass --assets DIR with .sh3f files",
         dir.string());
  return scenes::AssetLibrary::open(dir);
}

scenes::ApartmentOptions apartment_options(const GenerateOptions& options) {
  scenes::ApartmentOptions a;
  a.rooms = options.rooms;
  a.portals = options.portals;
  if (options.lighting == "day") a.lighting = scenes::ApartmentLighting::Day;
  else if (options.lighting == "night") a.lighting = scenes::ApartmentLighting::Night;
  else if (options.lighting != "mixed") fail("--lighting must be day, night or mixed, got '{}'", options.lighting);
  return a;
}

nlohmann::json generate_all(const GenerateOptions& options, const std::filesystem::path& out) {
  nlohmann::json rooms = nlohmann::json::array();
  const bool apartments = options.preset == "apartment";
  const scenes::RoomPreset preset = apartments ? scenes::RoomPreset::Mini : scenes::parse_room_preset(options.preset);
  const scenes::AssetLibrary library = apartments ? open_furniture_library(options.assets) : scenes::AssetLibrary();
  Progress progress(apartments ? "generating apartments" : "generating rooms", static_cast<uint64_t>(options.count),
                    apartments ? "apartments" : "rooms");
  for (int i = 0; i < options.count; ++i) {
    if (apartments)
      rooms.push_back(to_json(scenes::generate_apartment(out, i, options.seed, library, apartment_options(options)), i));
    else
      rooms.push_back(to_json(scenes::generate_room(out, i, options.seed, preset), i));
    progress.advance();
  }
  return rooms;
}

void run(const GenerateOptions& options) {
  if (options.count < 1) fail("--count must be at least 1, got {}", options.count);
  if (options.rooms != 0 && (options.rooms < scenes::kMinApartmentRooms || options.rooms > scenes::kMaxApartmentRooms))
    fail("--rooms must be 0 (from the seed) or {} to {}, got {}", scenes::kMinApartmentRooms, scenes::kMaxApartmentRooms,
         options.rooms);
  const std::filesystem::path out(options.out);
  ensure_writable_directory(out);
  const nlohmann::json rooms = generate_all(options, out);
  // No timestamps: the same command writes the same bytes.
  const nlohmann::json summary = {{"generator", std::string("phyir ") + PHYIR_VERSION},
                                  {"preset", options.preset},
                                  {"seed", options.seed},
                                  {"count", options.count},
                                  {"rooms", rooms}};
  write_file_atomic(out / "rooms.json", summary.dump(2) + "\n");
  spdlog::info("wrote {} {} and rooms.json to {}", options.count,
               options.preset == "apartment" ? "apartment(s)" : options.preset + " room(s)", out.string());
}

}  // namespace

void add_scenes_generate_command(CLI::App& scenes) {
  auto options = std::make_shared<GenerateOptions>();
  auto* cmd = scenes.add_subcommand(
      "generate",
      "Generate procedural indoor rooms as glTF 2.0 (room_<i>.gltf + .bin + PNG textures) and a "
      "rooms.json summary. The same --seed, --count and --preset give byte-identical files.");
  cmd->add_option("--out", options->out, "Output folder (created if missing)")->required();
  cmd->add_option("--count", options->count, "Number of rooms, written as room_0 ... room_<count-1>")
      ->capture_default_str();
  // strtoull would otherwise wrap "-3" round to 2^64 - 3.
  const CLI::Validator not_negative(
      [](std::string& value) { return value.rfind('-', 0) == 0 ? "must not be negative, got " + value : std::string(); },
      "");
  cmd->add_option("--seed", options->seed, "Seed of the series; room i depends only on (seed, i, preset)")
      ->check(not_negative)
      ->capture_default_str();
  cmd->add_option("--preset", options->preset,
                  "mini: small rectangular rooms, one ceiling light, few triangles; "
                  "hard: rectangular or L-shaped rooms with mirrors, metals, glass, small bright "
                  "lights and thin geometry; diffuse: a mini layout with only rough, untextured, "
                  "non-metallic materials; apartment: 2 to 6 furnished rooms from a Sweet Home 3D "
                  "furniture library, by day (sky and sun) or night (lamps) (docs/apartments.md)")
      ->capture_default_str();
  cmd->add_option("--assets", options->assets,
                  "apartment: folder of .sh3f furniture libraries (Debian: sweethome3d-furniture)")
      ->capture_default_str();
  cmd->add_option("--lighting", options->lighting, "apartment: day, night, or mixed (even apartments by day, odd ones at night)")
      ->capture_default_str();
  cmd->add_option("--rooms", options->rooms, "apartment: rooms per apartment, 2 to 6; 0 draws it from the seed")
      ->capture_default_str();
  cmd->add_flag("--portals", options->portals,
                "apartment: declare the windows as light portals, through which the renderers sample the sky "
                "(docs/gltf-support.md#light-portals)");
  cmd->callback([options] { run(*options); });
}

}  // namespace phyir::cli
