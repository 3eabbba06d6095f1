// A placed piece's frame, and the cache of loaded models.
#include <glm/gtc/matrix_transform.hpp>

#include "phyir/scenes/apartment_furnishing.h"

namespace phyir::scenes {

glm::vec3 PlacedAsset::size() const { return entry->size_m * scale; }

glm::vec3 PlacedAsset::front() const {
  static const glm::vec3 kFronts[4] = {{0, 0, 1}, {1, 0, 0}, {0, 0, -1}, {-1, 0, 0}};
  return kFronts[((quarter_turns % 4) + 4) % 4];
}

Box3 PlacedAsset::bounds() const {
  glm::vec3 s = size();
  if (quarter_turns % 2 != 0) std::swap(s.x, s.z);
  return {position - glm::vec3(0.5f * s.x, 0.0f, 0.5f * s.z), position + glm::vec3(0.5f * s.x, s.y, 0.5f * s.z)};
}

glm::mat4 PlacedAsset::model_to_world() const {
  glm::mat4 m = glm::translate(glm::mat4(1.0f), position);
  m = glm::rotate(m, glm::half_pi<float>() * float(quarter_turns), glm::vec3(0.0f, 1.0f, 0.0f));
  return glm::scale(m, scale);
}

const AssetModel& AssetModelCache::get(const AssetEntry& entry) {
  const std::string key = entry.archive.string() + "|" + entry.id;
  auto it = models_.find(key);
  if (it == models_.end()) it = models_.emplace(key, std::make_unique<AssetModel>(load_model(entry))).first;
  return *it->second;
}

const char* apartment_lighting_name(ApartmentLighting lighting) {
  return lighting == ApartmentLighting::Day ? "day" : "night";
}

}  // namespace phyir::scenes
