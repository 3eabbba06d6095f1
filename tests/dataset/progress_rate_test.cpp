// The dataset generator's progress line: core's Progress with its per-hour rate (views take
// seconds to minutes, so "0.0 views/s" would say nothing). The per-second default, which
// other commands use, keeps its form. Format only: no timing assertions.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "phyir/core/progress.h"

namespace phyir {
namespace {

using ::testing::ContainsRegex;
using ::testing::HasSubstr;
using ::testing::Not;

TEST(ProgressRate, PerHourShowsViewsPerHourAndTimeLeft) {
  Progress progress("dataset", 10, "views", false);
  progress.set_rate(ProgressRate::PerHour);
  progress.advance(4);
  const std::string line = progress.status_line();
  EXPECT_THAT(line, HasSubstr("dataset:  40% 4/10 views, "));
  EXPECT_THAT(line, ContainsRegex("views, [0-9]+ views/hour, [0-9hms?]+ elapsed, [0-9hms?]+ left$"));
  EXPECT_THAT(line, Not(HasSubstr("/s,")));
  EXPECT_THAT(progress.status_line(true), HasSubstr(" 0s left"));
}

TEST(ProgressRate, PerSecondIsTheDefault) {
  Progress progress("render", 8, "tiles", false);
  progress.advance(2);
  EXPECT_THAT(progress.status_line(), ContainsRegex("^render:  25% 2/8 tiles, [0-9]+\\.[0-9] tiles/s, "));
}

}  // namespace
}  // namespace phyir
