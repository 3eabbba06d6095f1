// The hostile-input corpus (tests/data/hostile, written by scripts/make_hostile_corpus.py;
// docs/robustness.md lists it): every file must fail with a phyir::Error whose message
// starts with the file's path and names the problem (expected.json), or, for the few marked
// "__loads__", load with finite geometry. Then every corpus file is mutated byte by byte
// (a small deterministic fuzzer that also runs under the sanitizers): only phyir::Error
// may come out, never a crash or another exception type.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "gltf_test_helpers.h"
#include "phyir/core/atomic_file.h"
#include "phyir/core/error.h"
#include "phyir/core/pcg32.h"
#include "phyir/scenes/gltf_loader.h"

namespace phyir::scenes {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::StartsWith;

const fs::path kCorpus = fs::path(PHYIR_TEST_DATA_DIR) / "hostile";

nlohmann::json expectations() {
  std::ifstream in(kCorpus / "expected.json");
  return nlohmann::json::parse(in).at("files");
}

bool all_finite(const Scene& scene) {
  for (const Mesh& m : scene.meshes)
    for (const glm::vec3& p : m.positions)
      if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) return false;
  return true;
}

TEST(HostileInputs, CorpusIsComplete) {
  // Every file in the folder has an expectation and vice versa.
  const nlohmann::json expected = expectations();
  size_t files = 0;
  for (const auto& entry : fs::directory_iterator(kCorpus)) {
    if (entry.path().filename() == "expected.json") continue;
    ++files;
    EXPECT_TRUE(expected.contains(entry.path().filename().string())) << entry.path();
  }
  EXPECT_EQ(files, expected.size());
  EXPECT_GE(files, 50u);
}

TEST(HostileInputs, EveryFileGivesAClearError) {
  size_t errors = 0, loads = 0;
  const nlohmann::json expected = expectations();
  for (const auto& [name, phrases] : expected.items()) {
    SCOPED_TRACE(name);
    const fs::path path = kCorpus / name;
    if (phrases.size() == 1 && phrases[0] == "__loads__") {
      const Scene scene = load_gltf(path);
      EXPECT_TRUE(all_finite(scene));
      ++loads;
      continue;
    }
    try {
      load_gltf(path);
      ADD_FAILURE() << name << " loaded without an error";
    } catch (const Error& e) {
      const std::string message = e.what();
      EXPECT_THAT(message, StartsWith(path.string() + ": "));
      for (const auto& phrase : phrases) EXPECT_THAT(message, HasSubstr(phrase.get<std::string>()));
      EXPECT_LT(message.size(), 2000u) << "messages stay readable";
      ++errors;
    }
  }
  std::printf("[hostile] corpus: %zu files give a clear error, %zu load\n", errors, loads);
}

// Loads `bytes` from a file named `name` in `dir`: returns "" when it loaded, else the
// phyir::Error message. Any other exception fails the test.
std::string try_load(const fs::path& dir, const std::string& name, const std::string& bytes) {
  const fs::path path = dir / name;
  test::write_bytes(path, bytes.data(), bytes.size());
  try {
    load_gltf(path);
  } catch (const Error& e) {
    return e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << name << ": " << typeid(e).name() << ": " << e.what();
  }
  return "";
}

TEST(HostileInputs, MutatedCorpusOnlyThrowsPhyirErrors) {
  // Per corpus file: 24 mutants, each with 1-4 random edits (byte flip, byte set to an
  // interesting value, a digit changed, a range deleted or duplicated). Deterministic.
  const fs::path dir = test::fresh_test_dir();
  Pcg32 rng(2024, 8);
  size_t mutants = 0, loaded = 0;
  const char kInteresting[] = {'\0', '\xff', '9', '-', '"', '[', '{', '}', ']', ',', 'e', '.'};
  for (const auto& entry : fs::directory_iterator(kCorpus)) {
    if (entry.path().filename() == "expected.json" || entry.file_size() > 20000) continue;
    const std::string original = read_file(entry.path());
    if (original.empty()) continue;
    for (int m = 0; m < 24; ++m) {
      std::string bytes = original;
      const int edits = 1 + static_cast<int>(rng.next_u32() % 4);
      for (int e = 0; e < edits && !bytes.empty(); ++e) {
        const size_t at = rng.next_u32() % bytes.size();
        switch (rng.next_u32() % 5) {
          case 0: bytes[at] = static_cast<char>(bytes[at] ^ (1u << (rng.next_u32() % 8))); break;
          case 1: bytes[at] = kInteresting[rng.next_u32() % sizeof kInteresting]; break;
          case 2: if (std::isdigit(static_cast<unsigned char>(bytes[at]))) bytes[at] = static_cast<char>('0' + rng.next_u32() % 10); break;
          case 3: bytes.erase(at, 1 + rng.next_u32() % 16); break;
          default: bytes.insert(at, bytes.substr(at, 1 + rng.next_u32() % 16)); break;
        }
      }
      const std::string name = entry.path().filename().string();
      if (try_load(dir, name, bytes).empty()) ++loaded;
      ++mutants;
    }
  }
  std::printf("[hostile] %zu mutants of the corpus: %zu loaded, the rest gave phyir::Error\n", mutants, loaded);
  EXPECT_GT(mutants, 1000u);
}

TEST(HostileInputs, DeepNodeChainDoesNotOverflowTheStack) {
  // 200,000 nested nodes: flattening must not recurse.
  nlohmann::json doc = {{"asset", {{"version", "2.0"}}}, {"scenes", {{{"nodes", {0}}}}}, {"scene", 0}};
  nlohmann::json nodes = nlohmann::json::array();
  constexpr int kDepth = 200000;
  for (int i = 0; i < kDepth; ++i)
    nodes.push_back(i + 1 < kDepth ? nlohmann::json{{"children", {i + 1}}} : nlohmann::json::object());
  doc["nodes"] = nodes;
  const fs::path dir = test::fresh_test_dir();
  const std::string text = doc.dump();
  EXPECT_EQ(try_load(dir, "deep.gltf", text), "");
}

}  // namespace
}  // namespace phyir::scenes
