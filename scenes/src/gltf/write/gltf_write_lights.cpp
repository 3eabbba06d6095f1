#include "gltf/write/gltf_write_lights.h"

#include <algorithm>
#include <cmath>

#include "gltf/write/gltf_write_values.h"
#include "phyir/core/error.h"

namespace phyir::scenes {

void GltfLight::set_radiometric(const glm::vec3& rgb) {
  const float largest = std::max({rgb.x, rgb.y, rgb.z});
  if (!(largest > 0.0f) || !std::isfinite(largest)) {  // black (or invalid, refused when written)
    color = glm::vec3(1.0f);
    intensity = std::isfinite(largest) ? 0.0f : largest;
    return;
  }
  color = glm::clamp(rgb / largest, 0.0f, 1.0f);
  intensity = largest * PunctualLight::kLumensPerWatt;
}

namespace gltf_write {

namespace {

using nlohmann::json;

constexpr float kHalfPi = 1.57079632679489661923f;

bool finite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

void check_light(const GltfLight& l, size_t index) {
  const auto bad = [&](const std::string& why) { fail("glTF writer: light {} ('{}') {}", index, l.name, why); };
  for (int c = 0; c < 3; ++c)
    if (!(l.color[c] >= 0.0f && l.color[c] <= 1.0f)) bad(fmt::format("color[{}] is {}: must be in [0, 1]", c, l.color[c]));
  if (!(l.intensity >= 0.0f) || !std::isfinite(l.intensity))
    bad(fmt::format("intensity is {}: must be a finite number >= 0", l.intensity));
  if (!finite(l.position)) bad("has a non-finite position");
  if (l.type != PunctualLight::Type::Point && !(finite(l.direction) && glm::length(l.direction) > 0.0f))
    bad("has no direction: it must be finite and non-zero");
  if (l.range && !(*l.range > 0.0f && std::isfinite(*l.range))) bad(fmt::format("range is {}: must be > 0", *l.range));
  if (l.type == PunctualLight::Type::Spot &&
      !(l.inner_cone_angle >= 0.0f && l.inner_cone_angle < l.outer_cone_angle && l.outer_cone_angle <= kHalfPi))
    bad(fmt::format("cone angles {} and {}: must satisfy 0 <= inner < outer <= pi/2", l.inner_cone_angle,
                    l.outer_cone_angle));
}

json light_json(const GltfLight& l) {
  json light = {{"name", l.name},
                {"type", to_string(l.type)},
                {"color", exact_array(l.color)},
                {"intensity", exact(l.intensity)}};
  if (l.type == PunctualLight::Type::Spot)
    light["spot"] = {{"innerConeAngle", exact(l.inner_cone_angle)}, {"outerConeAngle", exact(l.outer_cone_angle)}};
  if (l.range) light["range"] = exact(*l.range);
  return light;
}

json node_json(const GltfLight& l, size_t index) {
  json node = {{"name", l.name}, {"extensions", {{"KHR_lights_punctual", {{"light", index}}}}}};
  if (l.position != glm::vec3(0.0f)) node["translation"] = exact_array(l.position);
  if (l.type != PunctualLight::Type::Point) {
    const glm::vec4 q(rotation_towards(glm::normalize(glm::dvec3(l.direction))));
    if (q != glm::vec4(0.0f, 0.0f, 0.0f, 1.0f)) node["rotation"] = exact_array(q);
  }
  if (!l.extras.is_null()) node["extras"] = l.extras;
  return node;
}

}  // namespace

glm::dvec4 rotation_towards(const glm::dvec3& d) {
  // The half-way quaternion (cross(a, d), 1 + dot(a, d)) normalised, with a = -Z.
  const double w = 1.0 - d.z;
  if (w < 1e-12) return {0.0, 1.0, 0.0, 0.0};  // d = +Z: any half turn about an axis in the XY plane
  const glm::dvec4 q(d.y, -d.x, 0.0, w);
  return q / glm::length(q);
}

json encode_lights(const std::vector<GltfLight>& lights, json& nodes, json& scene_nodes) {
  json out = json::array();
  for (size_t i = 0; i < lights.size(); ++i) {
    check_light(lights[i], i);
    out.push_back(light_json(lights[i]));
    scene_nodes.push_back(nodes.size());
    nodes.push_back(node_json(lights[i], i));
  }
  return out;
}

}  // namespace gltf_write
}  // namespace phyir::scenes
