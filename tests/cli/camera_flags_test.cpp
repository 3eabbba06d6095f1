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
  struct Case {
    const char* args;
    int width, height;
  };
  const Case cases[] = {{"--width 256", 256, 128},
                        {"--height 100", 200, 100},
                        {"--width 300 --height 200", 300, 200},  // both given: kept
                        {"", 1024, 512}};                        // neither: the defaults
  for (const Case& c : cases) {
    const Size size = parse_size(c.args);
    EXPECT_EQ(size.width, c.width) << c.args;
    EXPECT_EQ(size.height, c.height) << c.args;
  }
}

}  // namespace
}  // namespace phyir::cli
