#include "bench_suite_runner.h"

#include <fstream>
#include <nlohmann/json.hpp>

#include "phyir/core/atomic_file.h"
#include "phyir/core/error.h"
#include "phyir/core/log.h"
#include "phyir/core/machine.h"
#include "phyir/scenes/bench_suite.h"

namespace phyir::cli {

namespace fs = std::filesystem;

void run_on_suite(const fs::path& suite_json, const fs::path& out, const std::string& result_file,
                  const std::function<void(const fs::path&, const std::optional<glm::vec3>&, const fs::path&)>& measure) {
  const std::vector<scenes::SuiteScene> suite = scenes::read_bench_suite(suite_json);
  nlohmann::json results = {{"suite", fs::absolute(suite_json).string()}, {"machine", machine_description()},
                            {"scenes", nlohmann::json::array()}};
  int failed = 0;
  for (size_t k = 0; k < suite.size(); ++k) {
    const scenes::SuiteScene& s = suite[k];
    spdlog::info("suite scene {}/{}: {} ({})", k + 1, suite.size(), s.name, s.what);
    const fs::path dir = out / s.name;
    nlohmann::json entry = {{"name", s.name}, {"what", s.what}, {"scene", s.scene.string()}};
    try {
      measure(s.scene, s.camera, dir);
      std::ifstream in(dir / result_file);
      entry["result"] = in ? nlohmann::json::parse(in, nullptr, false) : nlohmann::json();
    } catch (const std::exception& e) {
      spdlog::error("suite scene {}: {}", s.name, e.what());
      entry["error"] = e.what();
      ++failed;
    }
    results["scenes"].push_back(entry);
    write_file_atomic(out / "suite_results.json", results.dump(2) + "\n");  // kept if interrupted
  }
  spdlog::info("wrote {}", (out / "suite_results.json").string());
  if (failed) fail("{} of {} suite scenes failed (see above)", failed, suite.size());
}

}  // namespace phyir::cli
