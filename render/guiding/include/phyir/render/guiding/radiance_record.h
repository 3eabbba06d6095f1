#pragma once
// What a training path tells the guide: at a vertex, the radiance that arrived along the
// direction the path sampled there, and the density that direction was drawn with.
#include <vector>

#include <glm/glm.hpp>

namespace phyir::render::guiding {

struct RadianceRecord {
  glm::vec3 position{0.0f};
  glm::vec3 direction{0.0f, 0.0f, 1.0f};  // unit, world space, away from the vertex
  float radiance = 0.0f;                  // luminance of the incident radiance estimate
  float pdf = 0.0f;                       // solid-angle density that drew `direction`
};

// One worker's records of one chunk of work (a tile), in the order they were made.
using RecordBuffer = std::vector<RadianceRecord>;

}  // namespace phyir::render::guiding
