// phyir bench suite: generates the benchmark suite (scenes/bench_suite.h) that the other
// `phyir bench` commands measure with --suite.
#include <memory>

#include "commands.h"
#include "flag_registry.h"
#include "phyir/core/log.h"
#include "phyir/scenes/asset_library.h"
#include "phyir/scenes/bench_suite.h"

namespace phyir::cli {

namespace fs = std::filesystem;

namespace {

struct SuiteFlags {
  std::string out = "bench-suite";
  std::string assets = scenes::kDefaultAssetDir.string();
  std::string blender_room = (fs::path(PHYIR_SOURCE_ROOT) / "tests" / "data" / "gltf" / "blender_lit_room").string();
};

}  // namespace

void add_bench_suite_command(CLI::App& bench) {
  auto f = std::make_shared<SuiteFlags>();
  auto* cmd = bench.add_subcommand(
      "suite", "write the benchmark suite (mini, hard, three furnished apartment rooms by day and night, Blender's lit "
               "room) and its suite.json, for --suite");
  cmd->add_option("--out", f->out, "folder for the scenes and suite.json")->capture_default_str();
  sets(cmd, "asset_dir", cmd->add_option("--assets", f->assets, "furniture library (.sh3f files) for the apartments"))
      ->capture_default_str();
  cmd->add_option("--blender-room", f->blender_room, "folder of the Blender-exported lit_room.gltf")->capture_default_str();
  cmd->callback([f] {
    const auto suite = scenes::write_bench_suite(f->out, {f->assets, f->blender_room});
    for (const scenes::SuiteScene& s : suite) spdlog::info("  {:24s} {}", s.name, s.what);
    spdlog::info("wrote {} scenes and {}", suite.size(), (fs::path(f->out) / "suite.json").string());
  });
}

}  // namespace phyir::cli
