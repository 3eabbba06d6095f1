#pragma once
// `phyir bench ... --suite suite.json`: the same measurement on every scene of the benchmark
// suite (scenes/bench_suite.h), each into OUT/<name>/, then OUT/suite_results.json with every
// scene's result file side by side.
#include <glm/glm.hpp>

#include <filesystem>
#include <functional>
#include <optional>
#include <string>

#include "phyir/core/error.h"

namespace phyir::cli {

// Calls measure(scene, camera, out_dir) per scene, then collects out_dir/<result_file> of each
// into out/suite_results.json. A scene that fails is reported and the others still run; the
// call fails at the end if any did.
void run_on_suite(const std::filesystem::path& suite_json, const std::filesystem::path& out,
                  const std::string& result_file,
                  const std::function<void(const std::filesystem::path& scene, const std::optional<glm::vec3>& camera,
                                           const std::filesystem::path& out_dir)>& measure);

// One bench command's flags on their SCENE, or (with --suite) on every scene of the suite:
// Flags has scene, suite, camera and out; run measures one scene.
template <class Flags>
void run_scene_or_suite(const Flags& flags, void (*run)(const Flags&), const std::string& result_file,
                        const std::string& command) {
  if (flags.suite.empty() == flags.scene.empty()) fail("{}: give either a SCENE or --suite FILE", command);
  if (flags.suite.empty()) return run(flags);
  run_on_suite(flags.suite, flags.out, result_file,
               [&](const std::filesystem::path& scene, const std::optional<glm::vec3>& camera,
                   const std::filesystem::path& dir) {
                 Flags one = flags;
                 one.scene = scene.string(), one.camera = camera, one.out = dir.string();
                 run(one);
               });
}

}  // namespace phyir::cli
