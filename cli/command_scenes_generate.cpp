// phyir scenes generate: procedural indoor rooms as glTF 2.0, plus a rooms.json summary.
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
#include "phyir/scenes/room_generator.h"

namespace phyir::cli {

namespace {

struct GenerateOptions {
  std::string out;
  int count = 1;
  uint64_t seed = 1;
  std::string preset = "mini";
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

void run(const GenerateOptions& options) {
  const scenes::RoomPreset preset = scenes::parse_room_preset(options.preset);
  if (options.count < 1) fail("--count must be at least 1, got {}", options.count);
  const std::filesystem::path out(options.out);
  ensure_writable_directory(out);

  nlohmann::json rooms = nlohmann::json::array();
  {
    Progress progress("generating rooms", static_cast<uint64_t>(options.count), "rooms");
    for (int i = 0; i < options.count; ++i) {
      rooms.push_back(to_json(scenes::generate_room(out, i, options.seed, preset), i));
      progress.advance();
    }
  }
  // No timestamps: the same command writes the same bytes.
  const nlohmann::json summary = {{"generator", std::string("phyir ") + PHYIR_VERSION},
                                  {"preset", options.preset},
                                  {"seed", options.seed},
                                  {"count", options.count},
                                  {"rooms", rooms}};
  write_file_atomic(out / "rooms.json", summary.dump(2) + "\n");
  spdlog::info("wrote {} {} room(s) and rooms.json to {}", options.count, options.preset, out.string());
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
                  "non-metallic materials")
      ->capture_default_str();
  cmd->callback([options] { run(*options); });
}

}  // namespace phyir::cli
