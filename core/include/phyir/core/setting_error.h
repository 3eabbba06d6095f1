#pragma once
// A bad value of a named setting. Libraries name the setting as their settings struct does
// ("spp", "probe.grid_width"), never a command-line flag; the CLI knows which flag set it
// (cli/flags/flag_registry.h) and prints that instead.
#include <string>
#include <utility>

#include "phyir/core/error.h"

namespace phyir {

class SettingError : public Error {
 public:
  SettingError(std::string setting, const std::string& problem)
      : Error(setting + ": " + problem), setting_(std::move(setting)), problem_(problem) {}
  const std::string& setting() const { return setting_; }
  const std::string& problem() const { return problem_; }

 private:
  std::string setting_;
  std::string problem_;
};

template <typename... Args>
[[noreturn]] void fail_setting(std::string setting, fmt::format_string<Args...> format, Args&&... args) {
  throw SettingError(std::move(setting), fmt::format(format, std::forward<Args>(args)...));
}

}  // namespace phyir
