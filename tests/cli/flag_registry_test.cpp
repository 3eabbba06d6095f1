// Libraries name the setting a bad value belongs to; the CLI prints the flag that set it, in
// the command that ran (cli/flags/flag_registry.h). Every setting ProbeSettings and DatasetSettings
// check maps to a flag of the commands that set it, and the dataset's flags override the
// preset whatever their order.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "dataset_flags.h"
#include "flag_registry.h"
#include "probe_flags.h"
#include "sampling_flags.h"

namespace phyir::cli {
namespace {

using ::testing::HasSubstr;
using ::testing::StartsWith;

// The message main() prints for `settings.validate()` after parsing `args` on `command` of `app`.
template <class Settings>
std::string message_after(CLI::App& app, const std::string& args, const Settings& settings) {
  try {
    app.parse(args, false);
    settings.validate();
  } catch (const SettingError& e) {
    return setting_error_message(app, e);
  }
  return "no error";
}

TEST(FlagRegistry, NamesTheFlagOfTheCommandThatRan) {
  CLI::App app;
  render::RenderSettings a, b;
  int threads = 0;
  add_sampling_flags(app.add_subcommand("first"), a, threads);
  CLI::App* second = app.add_subcommand("second");
  sets(second, "spp", second->add_option("--paths", b.spp));
  app.parse("second --paths 3", false);
  EXPECT_EQ(flag_of_setting(app, "spp"), "--paths");
  EXPECT_EQ(setting_error_message(app, SettingError("spp", "0 must be positive")), "--paths: 0 must be positive");
  // A setting no flag of the command sets prints as it is.
  EXPECT_EQ(setting_error_message(app, SettingError("probe.hard_spp_factor", "0 must be between 1 and 1024")),
            "probe.hard_spp_factor: 0 must be between 1 and 1024");
}

TEST(FlagRegistry, EveryProbeSettingNamesItsFlag) {
  const std::pair<std::string, std::string> cases[] = {
      {"--probe-grid", "0x4"},         {"--probe-res", "16x0"},
      {"--probe-spp", "0"},            {"--probe-offset", "0"},
      {"--probe-cache-cell", "0"},     {"--probe-cache-spp", "0"},
      {"--probe-cache-direct-cells", "-1"}, {"--probe-spread-threshold", "0"},
      {"--probe-share-radius", "5"},   {"--probe-share-parallax", "0"},
      {"--probe-photons", "-1"},       {"--probe-mode", "fast"}};
  for (const auto& [flag, value] : cases) {
    CLI::App app;
    render::ProbeSettings probe;
    add_probe_flags(app.add_subcommand("render"), probe);
    EXPECT_THAT(message_after(app, "render " + flag + "=" + value, probe), StartsWith(flag + ": ")) << flag;
  }
}

TEST(FlagRegistry, ProbeFlagsShowTheStructsDefaults) {
  CLI::App app;
  render::ProbeSettings probe;
  add_probe_flags(&app, probe);
  const std::string help = app.help();
  const render::ProbeSettings defaults;
  EXPECT_THAT(help, HasSubstr(fmt::format("--probe-grid TEXT={}x{}", defaults.layout.grid_height,
                                          defaults.layout.grid_width)));
  EXPECT_THAT(help, HasSubstr(fmt::format("--probe-spp INT={}", defaults.spp)));
  EXPECT_THAT(help, HasSubstr(fmt::format("--probe-photons INT={}", defaults.photons_per_light)));
  EXPECT_THAT(help, HasSubstr("--probe-mode TEXT=cache"));
}

TEST(DatasetFlags, EveryCheckedSettingNamesItsFlag) {
  const std::pair<std::string, std::string> cases[] = {
      {"--width=100 --height=60", "--width/--height: "}, {"--spp=0", "--spp: "},
      {"--max-bounces=-1", "--max-bounces: "},           {"--probe-grid=0x4", "--probe-grid: "},
      {"--exposure-percentile=2", "--exposure-percentile: "}, {"--exposure-target=0", "--exposure-target: "},
      {"--exposure-jitter=-1", "--exposure-jitter: "},   {"--view=Bogus", "--view: "},
      {"--clearance=-1", "--clearance: "},               {"--min-spacing=-1", "--min-spacing: "},
      {"--views-per-scene=0", "--views-per-scene: "},    {"--split=0.5,0.5,0.5", "--split: "},
      {"--preset=huge", "--preset: "}};
  for (const auto& [args, start] : cases) {
    CLI::App app;
    DatasetSettingsFlags flags;
    add_dataset_settings_flags(app.add_subcommand("generate"), flags);
    std::string message = "no error";
    try {
      app.parse("generate " + args, false);
      flags.resolve();
    } catch (const SettingError& e) {
      message = setting_error_message(app, e);
    }
    EXPECT_THAT(message, StartsWith(start)) << args;
  }
}

TEST(DatasetFlags, FlagsOverrideThePresetInAnyOrder) {
  for (const std::string args : {"--spp 8 --preset tiny --probe-spp 3", "--preset tiny --spp 8 --probe-spp 3"}) {
    CLI::App app;
    DatasetSettingsFlags flags;
    add_dataset_settings_flags(&app, flags);
    app.parse(args, false);
    const dataset::DatasetSettings s = flags.resolve();
    const dataset::DatasetSettings tiny = dataset::preset_settings("tiny");
    EXPECT_EQ(s.preset, "tiny") << args;
    EXPECT_EQ(s.width, tiny.width) << args;
    EXPECT_EQ(s.probe.layout.grid_width, tiny.probe.layout.grid_width) << args;
    EXPECT_EQ(s.spp, 8) << args;
    EXPECT_EQ(s.probe.spp, 3) << args;
  }
}

TEST(DatasetFlags, ReplayRepeatsTheFlagsGivenInTheirOrder) {
  CLI::App app;
  DatasetSettingsFlags flags;
  add_dataset_settings_flags(&app, flags);
  app.parse("--exposure=-1.5 --no-probes --preset tiny --split 0.5,0.5,0", false);
  EXPECT_EQ(flags.replay(),
            (std::vector<std::string>{"--preset=tiny", "--no-probes", "--exposure=-1.5", "--split=0.5,0.5,0"}));
  const dataset::DatasetSettings s = flags.resolve();
  EXPECT_FALSE(s.probes);
  EXPECT_FALSE(s.input.auto_exposure);
  EXPECT_EQ(s.input.exposure_stops, -1.5f);
}

TEST(DatasetFlags, ProbesAndNoProbesContradict) {
  CLI::App app;
  DatasetSettingsFlags flags;
  add_dataset_settings_flags(&app, flags);
  app.parse("--probes --no-probes", false);
  EXPECT_THROW(flags.resolve(), Error);
}

}  // namespace
}  // namespace phyir::cli
