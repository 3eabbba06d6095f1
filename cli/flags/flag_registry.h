#pragma once
// Which flag sets which setting. Libraries report a bad value by the setting's name, as their
// settings struct calls it (phyir::SettingError, core/setting_error.h: "probe.spp", "width"),
// and know nothing of flags. Each flag group records, as it registers a flag on a command,
// the settings that flag sets there; main() prints a SettingError with the flag of the
// command that ran: "--probe-spp: 0 must be between 1 and 2^20". A setting no flag of that
// command sets prints as it is.
#include <CLI/CLI.hpp>

#include <string>

#include "phyir/core/setting_error.h"

namespace phyir::cli {

// Records that on `command`, `option` (one of its own) sets `setting`; returns `option`, for
// chaining. One option may set several settings ("probe.grid" and "probe.res" of a list).
CLI::Option* sets(CLI::App* command, const std::string& setting, CLI::Option* option);
// The same for a setting that more than one flag makes ("size": "--width/--height").
void sets(CLI::App* command, const std::string& setting, const std::string& flags);

// The flag that sets `setting` in the command `app` ran: its deepest parsed subcommand's, else
// the nearest parent's; empty when none records it.
std::string flag_of_setting(const CLI::App& app, const std::string& setting);

// `error` as the user reads it: "--flag: problem" where a flag sets the setting, else
// "setting: problem".
std::string setting_error_message(const CLI::App& app, const SettingError& error);

}  // namespace phyir::cli
