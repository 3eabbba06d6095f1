#include "phyir/dataset/futurehouse_layout.h"

#include <vector>

#include <fmt/format.h>

#include "phyir/core/error.h"
#include "phyir/core/setting_error.h"

namespace phyir::dataset::futurehouse {

namespace fs = std::filesystem;

const char* map_name(Map map) {
  switch (map) {
    case Map::Image: return "image";
    case Map::Albedo: return "albedo";
    case Map::Roughness: return "roughness";
    case Map::Metallic: return "metallic";
    case Map::Mask: return "mask";
    case Map::Normal: return "normal";
    case Map::Depth: return "depth";
  }
  return "?";
}

fs::path maps_folder(const fs::path& root, const std::string& plan) {
  return root / kDataFolder / plan / "ue4_result" / "CubemapData";
}

fs::path map_path(const fs::path& root, const std::string& plan, int index, Map map) {
  return maps_folder(root, plan) / fmt::format("{}_{}.hdr", index, map_name(map));
}

fs::path light_folder(const fs::path& root, const std::string& plan) {
  return root / kLightFolder / plan / "ue4_result" / "LightProbeData";
}

fs::path light_path(const fs::path& root, const std::string& plan, int index) {
  return light_folder(root, plan) / fmt::format("{}_light.exr", index);
}

fs::path sidecar_path(const fs::path& root, const std::string& plan, int index, const std::string& name) {
  return root / kSidecarFolder / plan / fmt::format("{}_{}.exr", index, name);
}

NormalAxes NormalAxes::parse(const std::string& text) {
  std::vector<std::string> items(1);
  for (char c : text) {
    if (c == ',') items.emplace_back();
    else items.back() += c;
  }
  if (items.size() != 3) fail_setting("normal_axes", "'{}': three comma-separated axes, e.g. x,y,z", text);
  NormalAxes axes;
  std::array<bool, 3> used = {false, false, false};
  for (size_t i = 0; i < 3; ++i) {
    std::string item = items[i];
    if (!item.empty() && (item[0] == '-' || item[0] == '+')) {
      axes.sign[i] = item[0] == '-' ? -1.0f : 1.0f;
      item.erase(0, 1);
    }
    if (item.size() != 1 || item[0] < 'x' || item[0] > 'z' || used[size_t(item[0] - 'x')])
      fail_setting("normal_axes", "'{}': give each of x, y, z once, with an optional sign (e.g. x,y,z or -z,y,x)", text);
    axes.source[i] = item[0] - 'x';
    used[size_t(item[0] - 'x')] = true;
  }
  return axes;
}

std::string NormalAxes::name() const {
  std::string out;
  for (int i = 0; i < 3; ++i) {
    if (i > 0) out += ',';
    if (sign[size_t(i)] < 0.0f) out += '-';
    out += char('x' + source[size_t(i)]);
  }
  return out;
}

glm::vec3 NormalAxes::to_ours(const glm::vec3& theirs) const {
  glm::vec3 ours;
  for (int i = 0; i < 3; ++i) ours[i] = sign[size_t(i)] * theirs[source[size_t(i)]];
  return ours;
}

glm::vec3 NormalAxes::to_theirs(const glm::vec3& ours) const {
  glm::vec3 theirs;
  for (int i = 0; i < 3; ++i) theirs[source[size_t(i)]] = sign[size_t(i)] * ours[i];
  return theirs;
}

}  // namespace phyir::dataset::futurehouse
