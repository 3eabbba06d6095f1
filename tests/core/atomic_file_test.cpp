#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>

#include "phyir/core/atomic_file.h"
#include "phyir/core/error.h"

namespace fs = std::filesystem;

TEST(AtomicFile, WritesAndReadsBack) {
  const fs::path dir = fs::temp_directory_path() / "phyir_atomic_test";
  fs::remove_all(dir);
  phyir::write_file_atomic(dir / "sub" / "a.json", "{\"x\": 1}\n");
  EXPECT_EQ(phyir::read_file(dir / "sub" / "a.json"), "{\"x\": 1}\n");
  phyir::write_file_atomic(dir / "sub" / "a.json", "new");
  EXPECT_EQ(phyir::read_file(dir / "sub" / "a.json"), "new");
  EXPECT_EQ(std::distance(fs::directory_iterator(dir / "sub"), fs::directory_iterator()), 1);
}

TEST(AtomicFile, TemporaryKeepsExtensionAndIsHidden) {
  const fs::path tmp = phyir::temporary_sibling("out/color.exr");
  EXPECT_EQ(tmp.extension(), ".exr");
  EXPECT_EQ(tmp.parent_path(), "out");
  EXPECT_EQ(tmp.filename().string()[0], '.');
}

TEST(AtomicFile, UnwritablePathNamesIt) {
  try {
    phyir::write_file_atomic("/proc/phyir_cannot_write_here/x.txt", "x");
    FAIL();
  } catch (const std::exception& e) {
    EXPECT_THAT(e.what(), testing::HasSubstr("phyir_cannot_write_here"));
  }
}
