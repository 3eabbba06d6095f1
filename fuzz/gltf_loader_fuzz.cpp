// libFuzzer target for the glTF/GLB loader: each input is written to a file in a private
// temporary folder (the loader reads paths, and resolves .bin/.png URIs beside them) and
// loaded with textures decoded. Only phyir::Error may come out; anything else (a crash, a
// sanitizer report, another exception, a malloc above -rss_limit_mb) is a finding.
// Built and run by scripts/fuzz.sh; docs/robustness.md.
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "phyir/core/error.h"
#include "phyir/core/log.h"
#include "phyir/scenes/gltf_loader.h"

namespace {

namespace fs = std::filesystem;

// One folder per fuzzing process (libFuzzer's -jobs/-workers run several).
const fs::path& input_path() {
  static const fs::path path = [] {
    const fs::path dir = fs::temp_directory_path() / ("phyir_gltf_fuzz." + std::to_string(::getpid()));
    fs::create_directories(dir);
    return dir / "input.gltf";
  }();
  return path;
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  phyir::init_logging();
  phyir::set_log_level("off");  // warnings about every mutant would drown the fuzzer's output
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const fs::path& path = input_path();
  {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  }
  try {
    phyir::scenes::load_gltf(path);
  } catch (const phyir::Error&) {
    // The expected outcome for malformed input.
  }
  return 0;
}
