#include "gltf/read/gltf_lights.h"

#include <cmath>
#include <limits>

#include "gltf/read/gltf_values.h"

namespace phyir::scenes::gltf {

namespace {

constexpr double kHalfPi = 1.57079632679489661923;

bool fits_float(const glm::dvec3& v) {
  for (int i = 0; i < 3; ++i)
    if (!(std::abs(v[i]) <= double(std::numeric_limits<float>::max()))) return false;
  return true;
}

// The light index a node's KHR_lights_punctual extension names, or -1 without one.
int node_light(const GltfContext& ctx, const tinygltf::Node& node, const std::string& where) {
  const auto it = node.extensions.find("KHR_lights_punctual");
  if (it == node.extensions.end()) return -1;
  const std::optional<int> light = integer_member(ctx, it->second, "light", where + " KHR_lights_punctual");
  if (!light) ctx.fail("{} has a KHR_lights_punctual extension without a 'light' index", where);
  if (!in_range(*light, ctx.model.lights.size()))
    ctx.fail("{} refers to light {}, which does not exist ({} lights)", where, *light, ctx.model.lights.size());
  return *light;
}

PunctualLight::Type light_type(const GltfContext& ctx, const tinygltf::Light& source, const std::string& where) {
  if (source.type == "point") return PunctualLight::Type::Point;
  if (source.type == "spot") return PunctualLight::Type::Spot;
  if (source.type == "directional") return PunctualLight::Type::Directional;
  ctx.fail("{} has type '{}': must be point, spot or directional", where, source.type);
}

// The file's values, checked against the extension's schema.
PunctualLight light_values(const GltfContext& ctx, int index) {
  const tinygltf::Light& source = ctx.model.lights[static_cast<size_t>(index)];
  const std::string where = label("light", index, ctx.model.lights);
  PunctualLight light;
  light.name = source.name.empty() ? where : source.name;
  light.type = light_type(ctx, source, where);
  if (!source.color.empty()) {
    if (source.color.size() != 3) ctx.fail("{} color has {} values: must have 3", where, source.color.size());
    for (int c = 0; c < 3; ++c) {
      const double v = source.color[size_t(c)];
      if (!(v >= 0.0 && v <= 1.0)) ctx.fail("{} color[{}] is {}: must be in [0, 1]", where, c, v);
      light.color[c] = float(v);
    }
  }
  const std::optional<float> intensity = to_finite_float(source.intensity);
  if (!intensity || *intensity < 0.0f) ctx.fail("{} intensity is {}: must be a finite number >= 0", where, source.intensity);
  light.intensity = *intensity;
  light.range = to_finite_float(source.range).value_or(0.0f);
  if (light.range < 0.0f) ctx.fail("{} range is {}: must be > 0", where, source.range);
  if (light.type == PunctualLight::Type::Spot) {
    const double inner = source.spot.innerConeAngle, outer = source.spot.outerConeAngle;
    if (!(inner >= 0.0 && inner < kHalfPi)) ctx.fail("{} spot.innerConeAngle is {}: must be in [0, pi/2)", where, inner);
    if (!(outer > 0.0 && outer <= kHalfPi)) ctx.fail("{} spot.outerConeAngle is {}: must be in (0, pi/2]", where, outer);
    if (inner > outer)
      ctx.fail("{} spot.innerConeAngle {} exceeds outerConeAngle {}: the inner cone must lie inside the outer", where,
               inner, outer);
    light.inner_cone_angle = float(inner);
    light.outer_cone_angle = float(outer);
  }
  return light;
}

}  // namespace

std::vector<PunctualLight> read_lights(const GltfContext& ctx, const std::vector<NodeInstance>& instances) {
  std::vector<PunctualLight> lights;
  for (const NodeInstance& instance : instances) {
    const tinygltf::Node& node = ctx.model.nodes[static_cast<size_t>(instance.node)];
    const std::string where = label("node", instance.node, ctx.model.nodes);
    const int index = node_light(ctx, node, where);
    if (index < 0) continue;
    PunctualLight light = light_values(ctx, index);
    // The node's scale moves the light but changes none of its properties (the extension).
    const glm::dvec3 position(instance.world[3]);
    const glm::dvec3 axis = glm::dmat3(instance.world) * glm::dvec3(0.0, 0.0, -1.0);
    const double length = glm::length(axis);
    if (!fits_float(position) || !std::isfinite(length))
      ctx.fail("{} places light {} at a non-finite position or direction: the node transforms overflow", where, index);
    if (light.type != PunctualLight::Type::Point && !(length > 0.0))
      ctx.fail("{} gives {} light {} no direction: its transform maps -Z to zero", where, to_string(light.type), index);
    light.position = glm::vec3(position);
    light.direction = length > 0.0 ? glm::vec3(axis / length) : glm::vec3(0.0f, 0.0f, -1.0f);
    lights.push_back(light);
  }
  return lights;
}

}  // namespace phyir::scenes::gltf
