#pragma once
// The glTF writer's KHR_lights_punctual lights, each on a node of its own placed by a
// translation and a rotation that turns the node's -Z onto the light's direction.
#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include <vector>

#include "phyir/scenes/gltf_writer.h"

namespace phyir::scenes::gltf_write {

// The unit quaternion (x, y, z, w) turning -Z onto the unit vector `direction`: the
// shortest arc, or half a turn about +Y when `direction` is +Z.
glm::dvec4 rotation_towards(const glm::dvec3& direction);

// Appends a node per light to `nodes` (and its index to `scene_nodes`); returns the
// extension's "lights" array. Fails naming the light on a value the extension forbids
// (colour outside [0, 1], negative or non-finite intensity, cone angles out of order, no
// direction, range <= 0).
nlohmann::json encode_lights(const std::vector<GltfLight>& lights, nlohmann::json& nodes, nlohmann::json& scene_nodes);

}  // namespace phyir::scenes::gltf_write
