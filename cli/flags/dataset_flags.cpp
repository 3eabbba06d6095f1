#include "dataset_flags.h"

#include <sstream>

#include <fmt/format.h>

#include "camera_flags.h"
#include "exposure_flag.h"
#include "flag_registry.h"
#include "phyir/core/error.h"
#include "probe_flags.h"
#include "sampling_flags.h"

namespace phyir::cli {

namespace {

// "tiny (64x32, 4 spp, 8x16 probes of 4x8 texels), cpu (...), paper (...)", from the presets.
std::string describe_presets() {
  std::string text;
  for (const std::string& name : dataset::preset_names()) {
    const dataset::DatasetSettings s = dataset::preset_settings(name);
    const render::ProbeLayout& l = s.probe.layout;
    text += fmt::format("{}{} ({}x{}, {} spp, {}x{} probes of {}x{} texels)", text.empty() ? "" : ", ", name, s.width,
                        s.height, s.spp, l.grid_height, l.grid_width, l.res_height, l.res_width);
  }
  return text;
}

dataset::SplitFractions parse_split(const std::string& text) {
  dataset::SplitFractions split;
  std::istringstream in(text);
  char c1 = 0, c2 = 0;
  if (!(in >> split.train >> c1 >> split.val >> c2 >> split.test) || c1 != ',' || c2 != ',' || !in.eof())
    fail("--split '{}' must be three fractions train,val,test (e.g. 0.8,0.1,0.1)", text);
  return split;
}

// What the dataset itself decides: its preset, views, seed and splits.
void add_bundle_flags(CLI::App* cmd, dataset::DatasetSettings& s) {
  sets(cmd, "preset",
       cmd->add_option_function<std::string>(
           "--preset", [&s](const std::string& name) { s = dataset::preset_settings(name); },
           "settings bundle: " + describe_presets()))
      ->default_str(s.preset);
  sets(cmd, "views_per_scene",
       cmd->add_option("--views-per-scene", s.views_per_scene,
                       "views per scene: its cameras, then its candidate viewpoints, then points sampled in free space"))
      ->capture_default_str();
  const CLI::Validator not_negative(
      [](std::string& value) { return value.rfind('-', 0) == 0 ? "must not be negative, got " + value : std::string(); },
      "");
  sets(cmd, "seed",
       cmd->add_option("--seed", s.seed, "dataset seed: viewpoints, per-view render seeds, exposure jitter, splits"))
      ->check(not_negative)
      ->capture_default_str();
}

// The views' viewpoints, preview and splits.
void add_view_flags(CLI::App* cmd, dataset::DatasetSettings& s) {
  sets(cmd, "preview_exposure",
       cmd->add_option("--preview-exposure", s.preview_exposure, "exposure of color.png, the render's preview, stops"))
      ->capture_default_str();
  sets(cmd, "viewpoints.clearance",
       cmd->add_option("--clearance", s.viewpoints.clearance, "sampled viewpoints: metres to the nearest surface"))
      ->capture_default_str();
  sets(cmd, "viewpoints.min_spacing",
       cmd->add_option("--min-spacing", s.viewpoints.min_spacing, "sampled viewpoints: metres to every other viewpoint"))
      ->capture_default_str();
  sets(cmd, "split",
       cmd->add_option_function<std::string>(
           "--split", [&s](const std::string& text) { s.split = parse_split(text); },
           "train,val,test fractions of the scenes"))
      ->default_str(fmt::format("{},{},{}", s.split.train, s.split.val, s.split.test));
}

}  // namespace

void add_dataset_settings_flags(CLI::App* cmd, DatasetSettingsFlags& f) {
  dataset::DatasetSettings& s = f.settings;
  const size_t before = cmd->get_options().size();
  // The order is the Slurm scripts' (replay) and --preset must come first (see the header).
  add_bundle_flags(cmd, s);
  add_image_size_flags(cmd, s.width, s.height);
  add_spp_flag(cmd, s.spp);
  add_max_bounces_flag(cmd, s.max_bounces);
  cmd->add_flag("--probes", s.probes, "render per-pixel light probes");
  cmd->add_flag_callback("--no-probes", [&s] { s.probes = false; }, "no light probes");
  add_probe_flags(cmd, s.probe, kAllProbeFlags & ~kProbePunctual);
  add_input_exposure_flags(cmd, s.input);
  add_view_flags(cmd, s);
  const std::vector<CLI::Option*> all = cmd->get_options();
  f.options.assign(all.begin() + std::ptrdiff_t(before), all.end());
  const std::string group = fmt::format("Dataset settings (shown: the {} preset's; --preset sets them all)", s.preset);
  for (CLI::Option* option : f.options) option->group(group);
}

dataset::DatasetSettings DatasetSettingsFlags::resolve() const {
  bool on = false, off = false;
  for (const CLI::Option* option : options) {
    on = on || (option->get_name() == "--probes" && option->count() > 0);
    off = off || (option->get_name() == "--no-probes" && option->count() > 0);
  }
  if (on && off) fail("--probes and --no-probes contradict each other");
  settings.validate();
  return settings;
}

std::vector<std::string> DatasetSettingsFlags::replay() const {
  std::vector<std::string> args;
  for (const CLI::Option* option : options) {
    if (option->count() == 0) continue;
    if (option->get_expected_max() == 0) args.push_back(option->get_name());
    else
      for (const std::string& value : option->results()) args.push_back(option->get_name() + "=" + value);
  }
  return args;
}

}  // namespace phyir::cli
