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

}  // namespace phyir
