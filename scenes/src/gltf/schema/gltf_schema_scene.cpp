// The node tree and what hangs on it (glTF 2.0 schema: scene, node, mesh*, camera*, skin,
// animation*).
#include <fmt/format.h>

#include "gltf/schema/gltf_schema_objects.h"

namespace phyir::scenes::gltf::schema {

namespace {

void check_primitive(const Object& primitive) {
  primitive.required("attributes");
  primitive.index_map("attributes");
  primitive.index("indices");
  primitive.index("material");
  primitive.integer_enum("mode", {0, 1, 2, 3, 4, 5, 6});
  primitive.index_maps("targets");
  check_primitive_extensions(primitive);
}

// Spec 5.12.3 / 5.13.4: "zfar MUST be greater than znear".
void check_depth_range(const Object& projection, std::optional<double> znear, std::optional<double> zfar) {
  if (znear && zfar && *zfar <= *znear)
    projection.fail_spec("zfar", is(projection.value().at("zfar")),
                         fmt::format("must be greater than znear ({})", *znear));
}

void check_perspective(const Object& perspective) {
  perspective.number("aspectRatio", above(0));
  perspective.required("yfov");
  perspective.number("yfov", above(0));
  perspective.required("znear");
  const std::optional<double> znear = perspective.number("znear", above(0));
  check_depth_range(perspective, znear, perspective.number("zfar", above(0)));
}

void check_orthographic(const Object& orthographic) {
  for (const char* key : {"xmag", "ymag"}) {
    orthographic.required(key);
    if (orthographic.number(key) == 0.0)
      orthographic.fail_spec(key, "is 0", "must not be zero (it would project everything onto a line)");
  }
  orthographic.required("zfar");
  orthographic.required("znear");
  const std::optional<double> znear = orthographic.number("znear", at_least(0));
  check_depth_range(orthographic, znear, orthographic.number("zfar", above(0)));
}

void check_channel_target(const Object& target) {
  target.index("node");
  target.required("path");
  // Not an enum check: KHR_animation_pointer adds the path "pointer".
  target.string("path");
}

void check_channel(const Object& channel) {
  channel.required("sampler");
  channel.index("sampler");
  channel.required("target");
  channel.object("target", "animation.channel.target", check_channel_target);
}

void check_animation_sampler(const Object& sampler) {
  sampler.required("input");
  sampler.index("input");
  sampler.required("output");
  sampler.index("output");
  sampler.string("interpolation");
}

}  // namespace

void check_scene(const Object& scene) { scene.index_array("nodes"); }

void check_node(const Object& node) {
  node.index("camera");
  node.index("skin");
  node.index("mesh");
  node.index_array("children");
  node.number_array("matrix", exactly(16));
  node.number_array("rotation", exactly(4), Range{-1, false, 1, false});
  node.number_array("scale", exactly(3));
  node.number_array("translation", exactly(3));
  node.number_array("weights", at_least_items(1));
  for (const char* part : {"translation", "rotation", "scale"}) node.forbid_together("matrix", part);
  node.depends_on("weights", "mesh");
  node.depends_on("skin", "mesh");
  check_node_extensions(node);
}

void check_mesh(const Object& mesh) {
  mesh.required("primitives");
  mesh.objects("primitives", "mesh.primitive", check_primitive);
  mesh.number_array("weights", at_least_items(1));
}

void check_camera(const Object& camera) {
  camera.required("type");
  const std::string type = *camera.string_enum("type", {"perspective", "orthographic"});
  camera.forbid_together("perspective", "orthographic");
  if (!camera.has(type.c_str()))
    camera.fail_spec(type, "is missing", fmt::format("required when type is \"{}\"", type));
  camera.object("perspective", "camera.perspective", check_perspective);
  camera.object("orthographic", "camera.orthographic", check_orthographic);
}

void check_skin(const Object& skin) {
  skin.index("inverseBindMatrices");
  skin.index("skeleton");
  skin.required("joints");
  skin.index_array("joints");
}

void check_animation(const Object& animation) {
  animation.required("channels");
  animation.objects("channels", "animation.channel", check_channel);
  animation.required("samplers");
  animation.objects("samplers", "animation.sampler", check_animation_sampler);
}

}  // namespace phyir::scenes::gltf::schema
