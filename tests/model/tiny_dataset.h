#pragma once
// A small dataset made by the real pipeline (`phyir scenes generate --preset mini` and
// `phyir dataset generate --preset tiny`, 64 x 32 views at 64 spp with a 16 x 32 grid of
// 8 x 16 probes), once per test process, removed at exit. Three scenes, one view each, one
// scene per split (train, val, test: the split's hash of these names and seed gives that).
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

namespace tiny {

struct Dataset {
  std::filesystem::path root;  // holds manifest.json; empty when the phyir binary is missing
  std::string error;           // why generating failed (the log's path)
  nlohmann::json manifest;
  // The folder of the first view of `split`.
  std::filesystem::path view(const std::string& split) const {
    for (const auto& v : manifest["views"])
      if (v["split"] == split) return root / v["dir"].get<std::string>();
    return {};
  }
};

inline const Dataset& dataset() {
  static const Dataset d = [] {
    Dataset out;
    const std::filesystem::path bin = PHYIR_BINARY;
    if (!std::filesystem::is_regular_file(bin)) return out;
    const std::filesystem::path dir =
        std::filesystem::temp_directory_path() / ("phyir_model_tiny_" + std::to_string(::getpid()));
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    std::atexit([] {
      std::error_code ec;
      std::filesystem::remove_all(
          std::filesystem::temp_directory_path() / ("phyir_model_tiny_" + std::to_string(::getpid())), ec);
    });
    const std::string log = " >> " + (dir / "log.txt").string() + " 2>&1";
    const bool ok =
        std::system((bin.string() + " scenes generate --out " + (dir / "rooms").string() +
                     " --count 3 --seed 2 --preset mini" + log).c_str()) == 0 &&
        std::system((bin.string() + " dataset generate --scenes " + (dir / "rooms").string() + " --out " +
                     (dir / "data").string() +
                     " --preset tiny --spp 64 --probe-grid 16x32 --probe-res 8x16 --views-per-scene 1"
                     " --split 0.34,0.33,0.33 --threads 2 --quiet" + log).c_str()) == 0;
    if (!ok) {
      out.error = "generating the tiny dataset failed; see " + (dir / "log.txt").string();
      return out;
    }
    out.root = dir / "data";
    std::ifstream in(out.root / "manifest.json");
    out.manifest = nlohmann::json::parse(in);
    return out;
  }();
  return d;
}

}  // namespace tiny
