#pragma once
// What every stage of the glTF loader shares: the file name for messages, the warning
// sink and (once parsed) the tinygltf model. Errors and warnings start with the file,
// then name the object: "room.gltf: accessor 7 (POSITION of mesh 0 'wall' primitive 0) ...".
#include <fmt/format.h>

#include <string>
#include <utility>
#include <vector>

#include "gltf/read/gltf_tinygltf.h"
#include "phyir/core/error.h"
#include "phyir/core/log.h"

namespace phyir::scenes::gltf {

class Diagnostics {
 public:
  Diagnostics(std::string file, std::vector<std::string>& warnings)
      : file_(std::move(file)), warnings_(warnings) {}

  const std::string& file() const { return file_; }

  template <typename... Args>
  [[noreturn]] void fail(fmt::format_string<Args...> format, Args&&... args) const {
    phyir::fail("{}: {}", file_, fmt::format(format, std::forward<Args>(args)...));
  }

  // Kept in Scene::warnings (without the file name: the scene knows its source) and logged.
  template <typename... Args>
  void warn(fmt::format_string<Args...> format, Args&&... args) const {
    std::string message = fmt::format(format, std::forward<Args>(args)...);
    spdlog::warn("{}: {}", file_, message);
    warnings_.push_back(std::move(message));
  }

 private:
  std::string file_;
  std::vector<std::string>& warnings_;
};

struct GltfContext : Diagnostics {
  GltfContext(const Diagnostics& diagnostics, const tinygltf::Model& parsed)
      : Diagnostics(diagnostics), model(parsed) {}
  const tinygltf::Model& model;
};

// "mesh 2 'Chair'" or "mesh 2" when unnamed: how messages refer to top-level objects.
template <typename T>
std::string label(const char* kind, int index, const std::vector<T>& items) {
  const bool named = index >= 0 && static_cast<size_t>(index) < items.size() &&
                     !items[static_cast<size_t>(index)].name.empty();
  return named ? fmt::format("{} {} '{}'", kind, index, items[static_cast<size_t>(index)].name)
               : fmt::format("{} {}", kind, index);
}

inline bool in_range(int index, size_t size) { return index >= 0 && static_cast<size_t>(index) < size; }

}  // namespace phyir::scenes::gltf
