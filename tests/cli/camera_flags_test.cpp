// --width or --height alone: the other follows at 2:1, the panorama's aspect, rather than
// keeping its own default (a 256-wide panorama 512 high would be stretched 4:1).
#include <gtest/gtest.h>

#include "camera_flags.h"

namespace phyir::cli {
namespace {

struct Size {
  int width = 1024, height = 512;
};

Size parse_size(const std::string& args) {
  CLI::App app;
  Size size;
  add_image_size_flags(app.add_subcommand("render"), size.width, size.height);
  app.parse("render " + args, false);
  return size;
}

TEST(CameraFlags, OneSideGivenTheOtherFollowsAtTwoToOne) {
  const Size width_only = parse_size("--width 256");
  EXPECT_EQ(width_only.width, 256);
  EXPECT_EQ(width_only.height, 128);
  const Size height_only = parse_size("--height 100");
  EXPECT_EQ(height_only.width, 200);
  EXPECT_EQ(height_only.height, 100);
}

TEST(CameraFlags, BothGivenOrNeitherAreKept) {
  const Size both = parse_size("--width 300 --height 200");
  EXPECT_EQ(both.width, 300);
  EXPECT_EQ(both.height, 200);
  const Size neither = parse_size("");
  EXPECT_EQ(neither.width, 1024);
  EXPECT_EQ(neither.height, 512);
}

}  // namespace
}  // namespace phyir::cli
