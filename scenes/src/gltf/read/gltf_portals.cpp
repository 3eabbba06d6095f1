#include "gltf/read/gltf_portals.h"

#include <cmath>

#include "gltf/read/gltf_values.h"

namespace phyir::scenes::gltf {

namespace {

glm::vec3 portal_vector(const GltfContext& ctx, const tinygltf::Value& entry, const char* name,
                        const std::string& where) {
  const tinygltf::Value* value = member(entry, name);
  const std::optional<glm::vec3> v = value != nullptr ? as_vec3(*value) : std::nullopt;
  if (!v || !std::isfinite(v->x) || !std::isfinite(v->y) || !std::isfinite(v->z))
    ctx.fail("{} needs '{}': three finite numbers (world space, metres)", where, name);
  return *v;
}

Portal read_portal(const GltfContext& ctx, const tinygltf::Value& entry, const std::string& where) {
  if (!entry.IsObject()) ctx.fail("{} is not an object with corner, edge_u and edge_v", where);
  for (const std::string& key : entry.Keys())
    if (key != "corner" && key != "edge_u" && key != "edge_v")
      ctx.fail("{} has an unknown member '{}': the members are corner, edge_u and edge_v", where, key);
  Portal p{portal_vector(ctx, entry, "corner", where), portal_vector(ctx, entry, "edge_u", where),
           portal_vector(ctx, entry, "edge_v", where)};
  const float area = glm::length(glm::cross(p.edge_u, p.edge_v));
  if (!(area > 1e-8f) || !std::isfinite(area))
    ctx.fail("{}: edge_u and edge_v span no area (parallel or zero): a portal is a parallelogram", where);
  return p;
}

}  // namespace

std::vector<Portal> read_portals(const GltfContext& ctx, int scene) {
  if (scene < 0) return {};
  const tinygltf::Value* phyir = member(ctx.model.scenes[static_cast<size_t>(scene)].extras, "phyir");
  const tinygltf::Value* list = phyir != nullptr ? member(*phyir, "portals") : nullptr;
  if (list == nullptr) return {};
  const std::string where = fmt::format("scene {} extras.phyir.portals", scene);
  if (!list->IsArray()) ctx.fail("{} is not an array of portals", where);
  std::vector<Portal> portals;
  for (size_t i = 0; i < list->ArrayLen(); ++i)
    portals.push_back(read_portal(ctx, list->Get(static_cast<int>(i)), fmt::format("{} entry {}", where, i)));
  return portals;
}

}  // namespace phyir::scenes::gltf
