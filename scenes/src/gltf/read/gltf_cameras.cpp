#include "gltf/read/gltf_cameras.h"

#include <cmath>

#include "gltf/read/gltf_values.h"
#include "phyir/core/safe_math.h"

namespace phyir::scenes::gltf {

Camera make_camera(const GltfContext& ctx, const NodeInstance& instance) {
  const tinygltf::Node& node = ctx.model.nodes[static_cast<size_t>(instance.node)];
  const std::string node_name = label("node", instance.node, ctx.model.nodes);
  if (!in_range(node.camera, ctx.model.cameras.size()))
    ctx.fail("{} refers to camera {}, which does not exist ({} cameras)", node_name, node.camera,
             ctx.model.cameras.size());
  const tinygltf::Camera& source = ctx.model.cameras[static_cast<size_t>(node.camera)];
  const std::string where = label("camera", node.camera, ctx.model.cameras);

  Camera camera;
  camera.name = !source.name.empty() ? source.name : !node.name.empty() ? node.name : where;
  const glm::dmat3 linear(instance.world);
  camera.position = glm::vec3(instance.world[3]);
  camera.forward =
      safe_normalize(glm::vec3(linear * glm::dvec3(0.0, 0.0, -1.0)), glm::vec3(0.0f, 0.0f, -1.0f));
  camera.up = safe_normalize(glm::vec3(linear * glm::dvec3(0.0, 1.0, 0.0)), glm::vec3(0.0f, 1.0f, 0.0f));

  if (source.type == "orthographic") {
    camera.perspective = false;
    camera.znear = to_finite_float(source.orthographic.znear).value_or(0.0f);
    camera.zfar = to_finite_float(source.orthographic.zfar).value_or(0.0f);
    ctx.warn(
        "{} (on {}) is orthographic: kept with perspective=false; renderers that need a perspective "
        "camera skip it",
        where, node_name);
    return camera;
  }
  if (source.type != "perspective") ctx.fail("{} has unknown type '{}'", where, source.type);
  const tinygltf::PerspectiveCamera& p = source.perspective;
  if (!(p.yfov > 0.0 && p.yfov < kPi)) ctx.fail("{} yfov {} is outside (0, pi)", where, p.yfov);
  camera.yfov = static_cast<float>(p.yfov);
  // Values outside float's range (JSON allows 1e300) count as absent.
  const float aspect = to_finite_float(p.aspectRatio).value_or(0.0f);
  camera.aspect_ratio = aspect > 0.0f ? aspect : 0.0f;
  const float znear = to_finite_float(p.znear).value_or(0.0f);
  if (znear > 0.0f) camera.znear = znear;
  const float zfar = to_finite_float(p.zfar).value_or(0.0f);
  camera.zfar = zfar > camera.znear ? zfar : 0.0f;
  return camera;
}

}  // namespace phyir::scenes::gltf
