#include "phyir/dataset/futurehouse_layout.h"

#include <fmt/format.h>

#include "phyir/core/error.h"

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
  NormalAxes axes;
  std::array<bool, 3> used = {false, false, false};
  size_t at = 0;
  for (int i = 0; i < 3; ++i) {
    const size_t end = text.find(',', at);
    std::string item = text.substr(at, end == std::string::npos ? std::string::npos : end - at);
    at = end == std::string::npos ? text.size() + 1 : end + 1;
    axes.sign[size_t(i)] = 1.0f;
    if (!item.empty() && (item[0] == '-' || item[0] == '+')) {
      if (item[0] == '-') axes.sign[size_t(i)] = -1.0f;
      item.erase(0, 1);
    }
    if (item.size() != 1 || item[0] < 'x' || item[0] > 'z' || used[size_t(item[0] - 'x')])
      fail("--normal-axes '{}': give each of x, y, z once, with an optional sign (e.g. x,y,z or -z,y,x)", text);
    axes.source[size_t(i)] = item[0] - 'x';
    used[size_t(item[0] - 'x')] = true;
  }
  if (at != text.size() + 1) fail("--normal-axes '{}': three comma-separated axes, e.g. x,y,z", text);
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
