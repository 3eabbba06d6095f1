#pragma once
// One exception type for every user-facing failure. Messages name the file, the
// object and the value ("room.gltf: accessor 7 (POSITION) reads past buffer 0"),
// so the CLI prints them verbatim and exits non-zero.
#include <fmt/format.h>

#include <stdexcept>
#include <string>

namespace phyir {

class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& message) : std::runtime_error(message) {}
};

template <typename... Args>
[[noreturn]] void fail(fmt::format_string<Args...> format, Args&&... args) {
  throw Error(fmt::format(format, std::forward<Args>(args)...));
}

// A bad value of a named setting. Libraries name the setting as their settings struct does
// ("spp", "probe.grid_width"), never a command-line flag; the CLI knows which flag set it
// (cli/flag_registry.h) and prints that instead. what() reads "<setting>: <problem>".
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
