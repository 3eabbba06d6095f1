#pragma once
// The schema test's data: one valid file that has every object type of glTF 2.0 and every
// extension the schema check knows, and mutations of it that each break one rule, with the
// message the loader must give and the Khronos validator's verdict.
#include <nlohmann/json.hpp>

#include <functional>
#include <string>
#include <vector>

namespace phyir::scenes::test {

using nlohmann::json;

// textured_quad.gltf (its .bin and texture copied beside) plus a second buffer as a data URI
// (animation times and translations, a sparse index and value), cameras, lights, a skin, an
// animation, a sparse accessor and material extensions. The Khronos validator finds no error.
inline json schema_base_document() {
  return R"({
  "asset": {"version": "2.0", "generator": "phyir schema test"},
  "extensionsUsed": ["KHR_lights_punctual", "KHR_materials_emissive_strength", "KHR_materials_ior",
                     "KHR_materials_transmission", "KHR_materials_specular", "KHR_texture_transform"],
  "extensions": {"KHR_lights_punctual": {"lights": [
    {"name": "bulb", "type": "point", "color": [1, 0.9, 0.8], "intensity": 10, "range": 5},
    {"name": "cone", "type": "spot", "spot": {"innerConeAngle": 0.2, "outerConeAngle": 0.6}}]}},
  "scene": 0,
  "scenes": [{"nodes": [0, 5, 3, 4]}],
  "nodes": [
    {"name": "quad", "mesh": 0},
    {"name": "cam", "camera": 0, "translation": [0, 0, 3]},
    {"name": "ortho", "camera": 1, "rotation": [0, 0, 0, 1]},
    {"name": "lamp", "scale": [1, 1, 1], "extensions": {"KHR_lights_punctual": {"light": 0}}},
    {"name": "spot", "matrix": [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 2, 0, 1],
     "extensions": {"KHR_lights_punctual": {"light": 1}}},
    {"name": "group", "children": [1, 2]}],
  "meshes": [{"name": "quad", "primitives": [
    {"attributes": {"POSITION": 0, "TEXCOORD_0": 1}, "indices": 2, "material": 0}]}],
  "materials": [{
    "name": "checker",
    "pbrMetallicRoughness": {
      "baseColorFactor": [1, 1, 1, 1], "metallicFactor": 0, "roughnessFactor": 0.5,
      "baseColorTexture": {"index": 0,
                           "extensions": {"KHR_texture_transform": {"offset": [0, 0], "scale": [2, 2], "rotation": 0.1}}}},
    "normalTexture": {"index": 0, "scale": 1},
    "occlusionTexture": {"index": 0, "strength": 0.5},
    "emissiveTexture": {"index": 0, "texCoord": 0},
    "emissiveFactor": [1, 1, 1],
    "alphaMode": "MASK", "alphaCutoff": 0.5, "doubleSided": true,
    "extensions": {
      "KHR_materials_emissive_strength": {"emissiveStrength": 2},
      "KHR_materials_ior": {"ior": 1.4},
      "KHR_materials_transmission": {"transmissionFactor": 0.5},
      "KHR_materials_specular": {"specularFactor": 0.5, "specularColorFactor": [1, 1, 1]}}}],
  "textures": [{"source": 0, "sampler": 0}],
  "samplers": [{"magFilter": 9728, "minFilter": 9729, "wrapS": 10497, "wrapT": 10497}],
  "images": [{"uri": "textures/checker.png"}],
  "cameras": [
    {"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.1, "zfar": 100, "aspectRatio": 1.5}},
    {"type": "orthographic", "orthographic": {"xmag": 1, "ymag": 1, "znear": 0, "zfar": 10}}],
  "skins": [{"joints": [1]}],
  "animations": [{"channels": [{"sampler": 0, "target": {"node": 1, "path": "translation"}}],
                  "samplers": [{"input": 3, "output": 4, "interpolation": "LINEAR"}]}],
  "accessors": [
    {"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]},
    {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC2"},
    {"bufferView": 2, "componentType": 5123, "count": 6, "type": "SCALAR"},
    {"bufferView": 3, "componentType": 5126, "count": 2, "type": "SCALAR", "min": [0], "max": [1]},
    {"bufferView": 4, "componentType": 5126, "count": 2, "type": "VEC3"},
    {"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0],
     "sparse": {"count": 1, "indices": {"bufferView": 5, "componentType": 5123}, "values": {"bufferView": 6}}}],
  "bufferViews": [
    {"buffer": 0, "byteOffset": 0, "byteLength": 48},
    {"buffer": 0, "byteOffset": 48, "byteLength": 32},
    {"buffer": 0, "byteOffset": 80, "byteLength": 12},
    {"buffer": 1, "byteOffset": 0, "byteLength": 8},
    {"buffer": 1, "byteOffset": 8, "byteLength": 24},
    {"buffer": 1, "byteOffset": 32, "byteLength": 2},
    {"buffer": 1, "byteOffset": 36, "byteLength": 12}],
  "buffers": [
    {"uri": "textured_quad.bin", "byteLength": 92},
    {"uri": "data:application/octet-stream;base64,AAAAAAAAgD8AAAAAAAAAAAAAAAAAAIA/AAAAAAAAAAABAAAAAAAAPwAAAD8AAAAA",
     "byteLength": 48}]
})"_json;
}

// What the Khronos glTF-Validator (2.0.0-dev.3.10) says of a mutation.
enum class Validator {
  kError,                    // an error: the file is invalid
  kOnlyWarns,                // VALUE_NOT_IN_LIST, a warning: values outside a schema enum
  kDoesNotKnowTheExtension,  // the validator skips the extension (draco, meshopt, instancing, basisu)
  kAccepts,                  // valid glTF that this loader refuses (an integer written 4.0)
};

using Edit = std::function<void(json&)>;

struct Mutation {
  std::string name;
  Edit edit;
  std::string message;  // the whole message after "<file>: "
  Validator validator = Validator::kError;
};

inline Edit set(const std::string& pointer, const json& value) {
  return [=](json& doc) { doc[json::json_pointer(pointer)] = value; };
}

inline Edit erase(const std::string& pointer) {
  return [=](json& doc) {
    const json::json_pointer p(pointer);
    doc[p.parent_pointer()].erase(p.back());
  };
}

inline Edit all(std::vector<Edit> edits) {
  return [=](json& doc) {
    for (const Edit& e : edits) e(doc);
  };
}

// Adds an extension object at `pointer` and declares the extension.
inline Edit add_extension(const std::string& pointer, const std::string& name, const json& value) {
  return all({set(pointer + "/extensions/" + name, value),
              [=](json& doc) { doc["extensionsUsed"].push_back(name); }});
}

// Messages name objects as the file does: "nodes[4] ('spot')" when the object has a name.
inline std::vector<Mutation> schema_mutations() {
  using V = Validator;
  const std::string mat = "materials[0] ('checker')";
  const std::string prim = "meshes[0] ('quad').primitives[0]";
  const std::string lights = "extensions.KHR_lights_punctual.lights";
  const std::string spot = lights + "[1] ('cone').spot";
  const std::string ext = mat + ".extensions.";
  const json meshopt = {
      {"buffer", 0}, {"byteLength", 48}, {"byteStride", 12}, {"count", 4}, {"mode", "ATTRIBUTES"}};
  const auto meshopt_with = [&](const json& patch) {
    json e = meshopt;
    e.merge_patch(patch);
    return add_extension("/bufferViews/0", "EXT_meshopt_compression", e);
  };
  const std::string meshopt_at = "bufferViews[0].extensions.EXT_meshopt_compression.";
  const std::string meshopt_rule = "EXT_meshopt_compression schema, bufferView.EXT_meshopt_compression.";
  const std::string draco_at = prim + ".extensions.KHR_draco_mesh_compression.";
  return {
      // glTF, asset, extension lists
      {"asset_missing", erase("/asset"), "asset is missing: required (glTF 2.0 schema, glTF.asset)"},
      {"asset_version_missing", erase("/asset/version"),
       "asset.version is missing: required (glTF 2.0 schema, asset.version)"},
      {"asset_version_three_parts", set("/asset/version", "2.0.1"),
       "asset.version is \"2.0.1\": must be <major>.<minor> such as \"2.0\" (glTF 2.0 schema, asset.version)"},
      {"asset_min_version_above_version", set("/asset/minVersion", "2.1"),
       "asset.minVersion is \"2.1\": must not be greater than version \"2.0\" (glTF 2.0 spec, "
       "asset.minVersion)"},
      {"scene_without_scenes", erase("/scenes"),
       "scene is given without scenes: needs scenes (glTF 2.0 schema, glTF.scene)"},
      {"scene_negative", set("/scene", -1), "scene is -1: must be >= 0 (glTF 2.0 schema, glTF.scene)"},
      {"scenes_empty", set("/scenes", json::array()),
       "scenes is empty: must have at least 1 item (glTF 2.0 schema, glTF.scenes)"},
      {"scene_nodes_repeat", set("/scenes/0/nodes", {0, 0, 5, 3, 4}),
       "scenes[0].nodes[1] is 0 again: items must be unique (glTF 2.0 schema, scene.nodes)"},
      {"extensions_used_repeat", [](json& d) { d["extensionsUsed"].push_back("KHR_lights_punctual"); },
       "extensionsUsed[6] is \"KHR_lights_punctual\" again: items must be unique (glTF 2.0 schema, "
       "glTF.extensionsUsed)"},
      {"extensions_required_not_used", set("/extensionsRequired", {"KHR_materials_variants"}),
       "extensionsRequired[0] is \"KHR_materials_variants\": must also be in extensionsUsed (glTF 2.0 spec, "
       "glTF.extensionsRequired)"},
      {"extension_not_declared", set("/nodes/0/extensions", {{"EXT_unknown", json::object()}}),
       "nodes[0] ('quad').extensions.EXT_unknown is not in extensionsUsed: every extension used must be "
       "listed there (glTF 2.0 spec, glTF.extensionsUsed)"},
      {"extension_not_an_object", set("/nodes/0/extensions", {{"KHR_lights_punctual", 5}}),
       "nodes[0] ('quad').extensions.KHR_lights_punctual is 5: must be an object (glTF 2.0 schema, extension)"},
      {"name_not_a_string", set("/nodes/5/name", 7),
       "nodes[5].name is 7: must be a string (glTF 2.0 schema, node.name)"},
      // buffer, bufferView
      {"buffer_byte_length_missing", erase("/buffers/0/byteLength"),
       "buffers[0].byteLength is missing: required (glTF 2.0 schema, buffer.byteLength)"},
      {"buffer_byte_length_zero", set("/buffers/0/byteLength", 0),
       "buffers[0].byteLength is 0: must be >= 1 (glTF 2.0 schema, buffer.byteLength)"},
      {"buffer_uri_number", set("/buffers/0/uri", 3),
       "buffers[0].uri is 3: must be a string (glTF 2.0 schema, buffer.uri)"},
      {"view_buffer_missing", erase("/bufferViews/0/buffer"),
       "bufferViews[0].buffer is missing: required (glTF 2.0 schema, bufferView.buffer)"},
      {"view_byte_length_zero", set("/bufferViews/0/byteLength", 0),
       "bufferViews[0].byteLength is 0: must be >= 1 (glTF 2.0 schema, bufferView.byteLength)"},
      {"view_byte_offset_negative", set("/bufferViews/1/byteOffset", -8),
       "bufferViews[1].byteOffset is -8: must be >= 0 (glTF 2.0 schema, bufferView.byteOffset)"},
      {"view_stride_2", set("/bufferViews/0/byteStride", 2),
       "bufferViews[0].byteStride is 2: must be in [4, 252] (glTF 2.0 schema, bufferView.byteStride)"},
      {"view_stride_13", set("/bufferViews/0/byteStride", 13),
       "bufferViews[0].byteStride is 13: must be a multiple of 4 (glTF 2.0 schema, bufferView.byteStride)"},
      {"view_target_1234", set("/bufferViews/0/target", 1234),
       "bufferViews[0].target is 1234: must be one of 34962, 34963 (glTF 2.0 schema, bufferView.target)",
       V::kOnlyWarns},
      // accessor
      {"accessor_byte_offset_negative", set("/accessors/0/byteOffset", -4),
       "accessors[0].byteOffset is -4: must be >= 0 (glTF 2.0 schema, accessor.byteOffset)"},
      {"accessor_byte_offset_string", set("/accessors/0/byteOffset", "4"),
       "accessors[0].byteOffset is \"4\": must be an integer (glTF 2.0 schema, accessor.byteOffset)"},
      {"accessor_byte_offset_without_view",
       all({erase("/accessors/4/bufferView"), set("/accessors/4/byteOffset", 0)}),
       "accessors[4].byteOffset is given without bufferView: needs bufferView (glTF 2.0 schema, "
       "accessor.byteOffset)"},
      {"accessor_count_zero", set("/accessors/0/count", 0),
       "accessors[0].count is 0: must be >= 1 (glTF 2.0 schema, accessor.count)"},
      {"accessor_count_fraction", set("/accessors/0/count", 1.5),
       "accessors[0].count is 1.5: must be an integer (glTF 2.0 schema, accessor.count)"},
      {"accessor_count_written_4_0", set("/accessors/0/count", 4.0),
       "accessors[0].count is 4.0: write it as 4 (integers written with a decimal point or exponent are "
       "valid glTF, but tinygltf 2.7 reads them as absent) (limitation of this loader, accessor.count)",
       V::kAccepts},
      {"accessor_component_type_5127", set("/accessors/0/componentType", 5127),
       "accessors[0].componentType is 5127: must be one of 5120, 5121, 5122, 5123, 5125, 5126 (glTF 2.0 "
       "schema, accessor.componentType)"},
      {"accessor_component_type_missing", erase("/accessors/0/componentType"),
       "accessors[0].componentType is missing: required (glTF 2.0 schema, accessor.componentType)"},
      {"accessor_type_vec5", set("/accessors/0/type", "VEC5"),
       "accessors[0].type is \"VEC5\": must be one of \"MAT2\", \"MAT3\", \"MAT4\", \"SCALAR\", \"VEC2\", "
       "\"VEC3\", \"VEC4\" (glTF 2.0 schema, accessor.type)"},
      {"accessor_normalized_float", set("/accessors/1/normalized", true),
       "accessors[1].normalized is true for componentType 5126: only 8- and 16-bit integer components may be "
       "normalized (glTF 2.0 spec, accessor.normalized)"},
      {"accessor_normalized_string", set("/accessors/1/normalized", "yes"),
       "accessors[1].normalized is \"yes\": must be true or false (glTF 2.0 schema, accessor.normalized)"},
      {"accessor_max_17_items", set("/accessors/0/max", json(std::vector<int>(17, 1))),
       "accessors[0].max has 17 items: must have 1 to 16 items (glTF 2.0 schema, accessor.max)"},
      {"accessor_min_2_items_for_vec3", set("/accessors/0/min", {0, 0}),
       "accessors[0].min has 2 items: must have 3, one per component of VEC3 (glTF 2.0 spec, accessor.min)"},
      {"sparse_count_zero", set("/accessors/5/sparse/count", 0),
       "accessors[5].sparse.count is 0: must be >= 1 (glTF 2.0 schema, accessor.sparse.count)"},
      {"sparse_indices_missing", erase("/accessors/5/sparse/indices"),
       "accessors[5].sparse.indices is missing: required (glTF 2.0 schema, accessor.sparse.indices)"},
      {"sparse_indices_float", set("/accessors/5/sparse/indices/componentType", 5126),
       "accessors[5].sparse.indices.componentType is 5126: must be one of 5121, 5123, 5125 (glTF 2.0 schema, "
       "accessor.sparse.indices.componentType)",
       V::kOnlyWarns},
      {"sparse_values_view_missing", erase("/accessors/5/sparse/values/bufferView"),
       "accessors[5].sparse.values.bufferView is missing: required (glTF 2.0 schema, "
       "accessor.sparse.values.bufferView)"},
      {"sparse_values_offset_negative", set("/accessors/5/sparse/values/byteOffset", -4),
       "accessors[5].sparse.values.byteOffset is -4: must be >= 0 (glTF 2.0 schema, "
       "accessor.sparse.values.byteOffset)"},
      // mesh, mesh.primitive
      {"mesh_primitives_empty", set("/meshes/0/primitives", json::array()),
       "meshes[0] ('quad').primitives is empty: must have at least 1 item (glTF 2.0 schema, mesh.primitives)"},
      {"mesh_weights_empty", set("/meshes/0/weights", json::array()),
       "meshes[0] ('quad').weights has 0 items: must have at least 1 (glTF 2.0 schema, mesh.weights)"},
      {"primitive_attributes_empty", set("/meshes/0/primitives/0/attributes", json::object()),
       prim +
           ".attributes is empty: must have at least 1 entry (glTF 2.0 schema, mesh.primitive.attributes)"},
      {"primitive_attribute_negative", set("/meshes/0/primitives/0/attributes/TEXCOORD_0", -1),
       prim + ".attributes.TEXCOORD_0 is -1: must be an index (an integer >= 0) (glTF 2.0 schema, "
              "mesh.primitive.attributes.TEXCOORD_0)"},
      {"primitive_mode_7", set("/meshes/0/primitives/0/mode", 7),
       prim + ".mode is 7: must be one of 0, 1, 2, 3, 4, 5, 6 (glTF 2.0 schema, mesh.primitive.mode)"},
      {"primitive_mode_string", set("/meshes/0/primitives/0/mode", "TRIANGLES"),
       prim + ".mode is \"TRIANGLES\": must be an integer (glTF 2.0 schema, mesh.primitive.mode)"},
      {"primitive_target_empty", set("/meshes/0/primitives/0/targets", json::array({json::object()})),
       prim + ".targets[0] is empty: must have at least 1 entry (glTF 2.0 schema, mesh.primitive.targets)"},
      // node
      {"node_matrix_15_numbers", set("/nodes/4/matrix", {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 2, 0}),
       "nodes[4] ('spot').matrix has 15 items: must have 16 items (glTF 2.0 schema, node.matrix)"},
      {"node_matrix_and_translation", set("/nodes/4/translation", {0, 0, 0}),
       "nodes[4] ('spot').matrix and translation are both given: only one of them is allowed (glTF 2.0 "
       "schema, node.matrix)"},
      {"node_rotation_3_numbers", set("/nodes/2/rotation", {0, 0, 0}),
       "nodes[2] ('ortho').rotation has 3 items: must have 4 items (glTF 2.0 schema, node.rotation)"},
      {"node_rotation_above_1", set("/nodes/2/rotation", {0, 0, 1.5, 1}),
       "nodes[2] ('ortho').rotation[2] is 1.5: must be in [-1, 1] (glTF 2.0 schema, node.rotation)"},
      {"node_scale_string_item", set("/nodes/3/scale", {1, "1", 1}),
       "nodes[3] ('lamp').scale[1] is \"1\": must be a number (glTF 2.0 schema, node.scale)"},
      {"node_translation_object", set("/nodes/1/translation", {{"x", 0}}),
       "nodes[1] ('cam').translation is {\"x\":0}: must be an array of numbers (glTF 2.0 schema, "
       "node.translation)"},
      {"node_children_repeat", set("/nodes/5/children", {1, 1, 2}),
       "nodes[5] ('group').children[1] is 1 again: items must be unique (glTF 2.0 schema, node.children)"},
      {"node_children_empty", set("/nodes/5/children", json::array()),
       "nodes[5] ('group').children is empty: must have at least 1 item (glTF 2.0 schema, node.children)"},
      {"node_mesh_negative", set("/nodes/0/mesh", -1),
       "nodes[0] ('quad').mesh is -1: must be >= 0 (glTF 2.0 schema, node.mesh)"},
      {"node_weights_without_mesh", set("/nodes/1/weights", {0.5}),
       "nodes[1] ('cam').weights is given without mesh: needs mesh (glTF 2.0 schema, node.weights)"},
      {"node_not_an_object", set("/nodes/5", 3),
       "nodes[5] is 3: must be an object (glTF 2.0 schema, glTF.nodes)"},
      // camera
      {"camera_type_fisheye", set("/cameras/0/type", "fisheye"),
       "cameras[0].type is \"fisheye\": must be one of \"orthographic\", \"perspective\" (glTF 2.0 schema, "
       "camera.type)",
       V::kOnlyWarns},
      {"camera_perspective_missing", erase("/cameras/0/perspective"),
       "cameras[0].perspective is missing: required when type is \"perspective\" (glTF 2.0 spec, "
       "camera.perspective)"},
      {"camera_perspective_and_orthographic",
       set("/cameras/0/orthographic", {{"xmag", 1}, {"ymag", 1}, {"znear", 0}, {"zfar", 10}}),
       "cameras[0].perspective and orthographic are both given: only one of them is allowed (glTF 2.0 "
       "schema, camera.perspective)"},
      {"perspective_yfov_zero", set("/cameras/0/perspective/yfov", 0),
       "cameras[0].perspective.yfov is 0: must be > 0 (glTF 2.0 schema, camera.perspective.yfov)"},
      {"perspective_yfov_string", set("/cameras/0/perspective/yfov", "0.8"),
       "cameras[0].perspective.yfov is \"0.8\": must be a number (glTF 2.0 schema, camera.perspective.yfov)"},
      {"perspective_znear_missing", erase("/cameras/0/perspective/znear"),
       "cameras[0].perspective.znear is missing: required (glTF 2.0 schema, camera.perspective.znear)"},
      {"perspective_zfar_below_znear", set("/cameras/0/perspective/zfar", 0.05),
       "cameras[0].perspective.zfar is 0.05: must be greater than znear (0.1) (glTF 2.0 spec, "
       "camera.perspective.zfar)"},
      {"perspective_aspect_ratio_zero", set("/cameras/0/perspective/aspectRatio", 0),
       "cameras[0].perspective.aspectRatio is 0: must be > 0 (glTF 2.0 schema, "
       "camera.perspective.aspectRatio)"},
      {"orthographic_xmag_zero", set("/cameras/1/orthographic/xmag", 0),
       "cameras[1].orthographic.xmag is 0: must not be zero (it would project everything onto a line) (glTF "
       "2.0 spec, camera.orthographic.xmag)"},
      {"orthographic_znear_negative", set("/cameras/1/orthographic/znear", -1),
       "cameras[1].orthographic.znear is -1: must be >= 0 (glTF 2.0 schema, camera.orthographic.znear)"},
      {"orthographic_zfar_missing", erase("/cameras/1/orthographic/zfar"),
       "cameras[1].orthographic.zfar is missing: required (glTF 2.0 schema, camera.orthographic.zfar)"},
      // image, texture, sampler
      {"image_without_uri", erase("/images/0/uri"),
       "images[0] has neither uri nor bufferView: exactly one of them is required (glTF 2.0 schema, image)"},
      {"image_view_without_mime_type", all({erase("/images/0/uri"), set("/images/0/bufferView", 2)}),
       "images[0].bufferView is given without mimeType: needs mimeType (glTF 2.0 schema, image.bufferView)"},
      {"image_uri_and_view", all({set("/images/0/bufferView", 2), set("/images/0/mimeType", "image/png")}),
       "images[0].uri and bufferView are both given: only one of them is allowed (glTF 2.0 schema, image.uri)"},
      {"image_mime_type_gif", set("/images/0/mimeType", "image/gif"),
       "images[0].mimeType is \"image/gif\": must be one of \"image/jpeg\", \"image/png\" (glTF 2.0 schema, "
       "image.mimeType)"},
      {"texture_source_negative", set("/textures/0/source", -1),
       "textures[0].source is -1: must be >= 0 (glTF 2.0 schema, texture.source)"},
      {"texture_sampler_fraction", set("/textures/0/sampler", 0.5),
       "textures[0].sampler is 0.5: must be an integer (glTF 2.0 schema, texture.sampler)"},
      {"sampler_wrap_s_1234", set("/samplers/0/wrapS", 1234),
       "samplers[0].wrapS is 1234: must be one of 33071, 33648, 10497 (glTF 2.0 schema, sampler.wrapS)",
       V::kOnlyWarns},
      {"sampler_wrap_t_1234", set("/samplers/0/wrapT", 1234),
       "samplers[0].wrapT is 1234: must be one of 33071, 33648, 10497 (glTF 2.0 schema, sampler.wrapT)",
       V::kOnlyWarns},
      {"sampler_mag_filter_mipmap", set("/samplers/0/magFilter", 9984),
       "samplers[0].magFilter is 9984: must be one of 9728, 9729 (glTF 2.0 schema, sampler.magFilter)",
       V::kOnlyWarns},
      {"sampler_min_filter_1", set("/samplers/0/minFilter", 1),
       "samplers[0].minFilter is 1: must be one of 9728, 9729, 9984, 9985, 9986, 9987 (glTF 2.0 schema, "
       "sampler.minFilter)",
       V::kOnlyWarns},
      // material
      {"alpha_mode_glass", set("/materials/0/alphaMode", "GLASS"),
       mat + ".alphaMode is \"GLASS\": must be one of \"BLEND\", \"MASK\", \"OPAQUE\" (glTF 2.0 schema, "
             "material.alphaMode)",
       V::kOnlyWarns},
      {"alpha_cutoff_negative", set("/materials/0/alphaCutoff", -0.5),
       mat + ".alphaCutoff is -0.5: must be >= 0 (glTF 2.0 schema, material.alphaCutoff)"},
      {"emissive_factor_negative", set("/materials/0/emissiveFactor", {-1, 0, 0}),
       mat + ".emissiveFactor[0] is -1: must be in [0, 1] (glTF 2.0 schema, material.emissiveFactor)"},
      {"emissive_factor_2_items", set("/materials/0/emissiveFactor", {1, 1}),
       mat + ".emissiveFactor has 2 items: must have 3 items (glTF 2.0 schema, material.emissiveFactor)"},
      {"base_color_factor_3_items", set("/materials/0/pbrMetallicRoughness/baseColorFactor", {1, 1, 1}),
       mat + ".pbrMetallicRoughness.baseColorFactor has 3 items: must have 4 items (glTF 2.0 schema, "
             "material.pbrMetallicRoughness.baseColorFactor)"},
      {"base_color_factor_1_5", set("/materials/0/pbrMetallicRoughness/baseColorFactor", {1, 1.5, 1, 1}),
       mat + ".pbrMetallicRoughness.baseColorFactor[1] is 1.5: must be in [0, 1] (glTF 2.0 schema, "
             "material.pbrMetallicRoughness.baseColorFactor)"},
      {"metallic_factor_1_5", set("/materials/0/pbrMetallicRoughness/metallicFactor", 1.5),
       mat + ".pbrMetallicRoughness.metallicFactor is 1.5: must be in [0, 1] (glTF 2.0 schema, "
             "material.pbrMetallicRoughness.metallicFactor)"},
      {"roughness_factor_negative", set("/materials/0/pbrMetallicRoughness/roughnessFactor", -0.1),
       mat + ".pbrMetallicRoughness.roughnessFactor is -0.1: must be in [0, 1] (glTF 2.0 schema, "
             "material.pbrMetallicRoughness.roughnessFactor)"},
      {"texture_info_index_missing", erase("/materials/0/pbrMetallicRoughness/baseColorTexture/index"),
       mat + ".pbrMetallicRoughness.baseColorTexture.index is missing: required (glTF 2.0 schema, "
             "textureInfo.index)"},
      {"texture_info_tex_coord_negative", set("/materials/0/emissiveTexture/texCoord", -1),
       mat + ".emissiveTexture.texCoord is -1: must be >= 0 (glTF 2.0 schema, textureInfo.texCoord)"},
      {"normal_scale_string", set("/materials/0/normalTexture/scale", "big"),
       mat + ".normalTexture.scale is \"big\": must be a number (glTF 2.0 schema, "
             "material.normalTextureInfo.scale)"},
      {"occlusion_strength_1_5", set("/materials/0/occlusionTexture/strength", 1.5),
       mat + ".occlusionTexture.strength is 1.5: must be in [0, 1] (glTF 2.0 schema, "
             "material.occlusionTextureInfo.strength)"},
      {"double_sided_number", set("/materials/0/doubleSided", 1),
       mat + ".doubleSided is 1: must be true or false (glTF 2.0 schema, material.doubleSided)"},
      {"pbr_not_an_object", set("/materials/0/pbrMetallicRoughness", {1}),
       mat + ".pbrMetallicRoughness is [1]: must be an object (glTF 2.0 schema, "
             "material.pbrMetallicRoughness)"},
      // skin, animation
      {"skin_joints_missing", erase("/skins/0/joints"),
       "skins[0].joints is missing: required (glTF 2.0 schema, skin.joints)"},
      {"skin_joints_repeat", set("/skins/0/joints", {1, 1}),
       "skins[0].joints[1] is 1 again: items must be unique (glTF 2.0 schema, skin.joints)"},
      {"skin_inverse_bind_matrices_negative", set("/skins/0/inverseBindMatrices", -1),
       "skins[0].inverseBindMatrices is -1: must be >= 0 (glTF 2.0 schema, skin.inverseBindMatrices)"},
      {"animation_channels_empty", set("/animations/0/channels", json::array()),
       "animations[0].channels is empty: must have at least 1 item (glTF 2.0 schema, animation.channels)"},
      {"animation_target_path_missing", erase("/animations/0/channels/0/target/path"),
       "animations[0].channels[0].target.path is missing: required (glTF 2.0 schema, "
       "animation.channel.target.path)"},
      {"animation_sampler_input_missing", erase("/animations/0/samplers/0/input"),
       "animations[0].samplers[0].input is missing: required (glTF 2.0 schema, animation.sampler.input)"},
      // KHR_lights_punctual
      {"lights_missing", erase("/extensions/KHR_lights_punctual/lights"),
       "extensions.KHR_lights_punctual.lights is missing: required (KHR_lights_punctual schema, "
       "glTF.KHR_lights_punctual.lights)"},
      {"light_type_laser", set("/extensions/KHR_lights_punctual/lights/0/type", "laser"),
       lights + "[0] ('bulb').type is \"laser\": must be one of \"directional\", \"point\", \"spot\" "
                "(KHR_lights_punctual schema, light.type)",
       V::kOnlyWarns},
      {"light_type_missing", erase("/extensions/KHR_lights_punctual/lights/0/type"),
       lights + "[0] ('bulb').type is missing: required (KHR_lights_punctual schema, light.type)"},
      {"light_color_2_items", set("/extensions/KHR_lights_punctual/lights/0/color", {1, 1}),
       lights +
           "[0] ('bulb').color has 2 items: must have 3 items (KHR_lights_punctual schema, light.color)"},
      {"light_color_above_1", set("/extensions/KHR_lights_punctual/lights/0/color", {1, 2, 1}),
       lights + "[0] ('bulb').color[1] is 2: must be in [0, 1] (KHR_lights_punctual schema, light.color)"},
      {"light_intensity_negative", set("/extensions/KHR_lights_punctual/lights/0/intensity", -1),
       lights + "[0] ('bulb').intensity is -1: must be >= 0 (KHR_lights_punctual schema, light.intensity)"},
      {"light_range_zero", set("/extensions/KHR_lights_punctual/lights/0/range", 0),
       lights + "[0] ('bulb').range is 0: must be > 0 (KHR_lights_punctual schema, light.range)"},
      {"light_spot_missing", erase("/extensions/KHR_lights_punctual/lights/1/spot"),
       lights + "[1] ('cone').spot is missing: required when type is \"spot\" (KHR_lights_punctual spec, "
                "light.spot)"},
      {"spot_outer_cone_2", set("/extensions/KHR_lights_punctual/lights/1/spot/outerConeAngle", 2.0),
       spot + ".outerConeAngle is 2.0: must be in (0, 1.5707963267948966] (KHR_lights_punctual schema, "
              "light.spot.outerConeAngle)"},
      {"spot_outer_cone_zero", set("/extensions/KHR_lights_punctual/lights/1/spot", {{"outerConeAngle", 0}}),
       spot + ".outerConeAngle is 0: must be in (0, 1.5707963267948966] (KHR_lights_punctual schema, "
              "light.spot.outerConeAngle)"},
      {"spot_inner_cone_negative", set("/extensions/KHR_lights_punctual/lights/1/spot/innerConeAngle", -0.1),
       spot + ".innerConeAngle is -0.1: must be in [0, 1.5707963267948966) (KHR_lights_punctual schema, "
              "light.spot.innerConeAngle)"},
      {"spot_inner_cone_above_half_pi",
       set("/extensions/KHR_lights_punctual/lights/1/spot",
           {{"innerConeAngle", 1.6}, {"outerConeAngle", 1.5}}),
       spot + ".innerConeAngle is 1.6: must be in [0, 1.5707963267948966) (KHR_lights_punctual schema, "
              "light.spot.innerConeAngle)"},
      {"spot_inner_cone_not_below_outer",
       set("/extensions/KHR_lights_punctual/lights/1/spot/innerConeAngle", 0.7),
       spot + ".innerConeAngle is 0.7 with outerConeAngle 0.6: must be less than outerConeAngle "
              "(KHR_lights_punctual spec, light.spot.innerConeAngle)"},
      {"node_light_missing", set("/nodes/3/extensions/KHR_lights_punctual", json::object()),
       "nodes[3] ('lamp').extensions.KHR_lights_punctual.light is missing: required (KHR_lights_punctual "
       "schema, node.KHR_lights_punctual.light)"},
      {"node_light_negative", set("/nodes/3/extensions/KHR_lights_punctual/light", -1),
       "nodes[3] ('lamp').extensions.KHR_lights_punctual.light is -1: must be >= 0 (KHR_lights_punctual "
       "schema, node.KHR_lights_punctual.light)"},
      // material extensions, KHR_texture_transform
      {"emissive_strength_negative",
       set("/materials/0/extensions/KHR_materials_emissive_strength/emissiveStrength", -1),
       ext + "KHR_materials_emissive_strength.emissiveStrength is -1: must be >= 0 "
             "(KHR_materials_emissive_strength schema, "
             "material.KHR_materials_emissive_strength.emissiveStrength)"},
      {"ior_0_5", set("/materials/0/extensions/KHR_materials_ior/ior", 0.5),
       ext + "KHR_materials_ior.ior is 0.5: must be 0 or >= 1 (KHR_materials_ior schema, "
             "material.KHR_materials_ior.ior)"},
      {"transmission_factor_1_5",
       set("/materials/0/extensions/KHR_materials_transmission/transmissionFactor", 1.5),
       ext + "KHR_materials_transmission.transmissionFactor is 1.5: must be in [0, 1] "
             "(KHR_materials_transmission schema, material.KHR_materials_transmission.transmissionFactor)"},
      {"transmission_texture_without_index",
       set("/materials/0/extensions/KHR_materials_transmission/transmissionTexture", {{"texCoord", 0}}),
       ext + "KHR_materials_transmission.transmissionTexture.index is missing: required "
             "(KHR_materials_transmission schema, textureInfo.index)"},
      {"specular_factor_1_5", set("/materials/0/extensions/KHR_materials_specular/specularFactor", 1.5),
       ext +
           "KHR_materials_specular.specularFactor is 1.5: must be in [0, 1] (KHR_materials_specular schema, "
           "material.KHR_materials_specular.specularFactor)"},
      {"specular_color_negative",
       set("/materials/0/extensions/KHR_materials_specular/specularColorFactor", {1, -1, 1}),
       ext + "KHR_materials_specular.specularColorFactor[1] is -1: must be >= 0 (KHR_materials_specular "
             "schema, material.KHR_materials_specular.specularColorFactor)"},
      {"specular_color_2_items",
       set("/materials/0/extensions/KHR_materials_specular/specularColorFactor", {1, 1}),
       ext + "KHR_materials_specular.specularColorFactor has 2 items: must have 3 items "
             "(KHR_materials_specular schema, material.KHR_materials_specular.specularColorFactor)"},
      {"texture_transform_offset_3_items",
       set("/materials/0/pbrMetallicRoughness/baseColorTexture/extensions/KHR_texture_transform/offset",
           {0, 0, 0}),
       mat + ".pbrMetallicRoughness.baseColorTexture.extensions.KHR_texture_transform.offset has 3 items: "
             "must have 2 items (KHR_texture_transform schema, textureInfo.KHR_texture_transform.offset)"},
      {"texture_transform_rotation_array",
       set("/materials/0/pbrMetallicRoughness/baseColorTexture/extensions/KHR_texture_transform/rotation",
           {0}),
       mat + ".pbrMetallicRoughness.baseColorTexture.extensions.KHR_texture_transform.rotation is [0]: must "
             "be a number (KHR_texture_transform schema, textureInfo.KHR_texture_transform.rotation)"},
      {"texture_transform_tex_coord_negative",
       set("/materials/0/pbrMetallicRoughness/baseColorTexture/extensions/KHR_texture_transform/texCoord",
           -1),
       mat + ".pbrMetallicRoughness.baseColorTexture.extensions.KHR_texture_transform.texCoord is -1: must "
             "be >= 0 (KHR_texture_transform schema, textureInfo.KHR_texture_transform.texCoord)"},
      // KHR_draco_mesh_compression, EXT_meshopt_compression, EXT_mesh_gpu_instancing, texture sources
      {"draco_without_buffer_view",
       add_extension("/meshes/0/primitives/0", "KHR_draco_mesh_compression",
                     {{"attributes", {{"POSITION", 0}}}}),
       draco_at + "bufferView is missing: required (KHR_draco_mesh_compression schema, "
                  "mesh.primitive.KHR_draco_mesh_compression.bufferView)",
       V::kDoesNotKnowTheExtension},
      {"draco_without_attributes",
       add_extension("/meshes/0/primitives/0", "KHR_draco_mesh_compression", {{"bufferView", 2}}),
       draco_at + "attributes is missing: required (KHR_draco_mesh_compression schema, "
                  "mesh.primitive.KHR_draco_mesh_compression.attributes)",
       V::kDoesNotKnowTheExtension},
      {"meshopt_mode_missing", meshopt_with({{"mode", nullptr}}),
       meshopt_at + "mode is missing: required (" + meshopt_rule + "mode)", V::kDoesNotKnowTheExtension},
      {"meshopt_mode_points", meshopt_with({{"mode", "POINTS"}}),
       meshopt_at + "mode is \"POINTS\": must be one of \"ATTRIBUTES\", \"INDICES\", \"TRIANGLES\" (" +
           meshopt_rule + "mode)",
       V::kDoesNotKnowTheExtension},
      {"meshopt_filter_log", meshopt_with({{"filter", "LOG"}}),
       meshopt_at +
           "filter is \"LOG\": must be one of \"EXPONENTIAL\", \"NONE\", \"OCTAHEDRAL\", \"QUATERNION\" (" +
           meshopt_rule + "filter)",
       V::kDoesNotKnowTheExtension},
      {"meshopt_count_zero", meshopt_with({{"count", 0}}),
       meshopt_at + "count is 0: must be >= 1 (" + meshopt_rule + "count)", V::kDoesNotKnowTheExtension},
      {"meshopt_stride_1", meshopt_with({{"byteStride", 1}}),
       meshopt_at + "byteStride is 1: must be in [2, 256] (" + meshopt_rule + "byteStride)",
       V::kDoesNotKnowTheExtension},
      {"meshopt_attributes_stride_6", meshopt_with({{"byteStride", 6}}),
       meshopt_at +
           "byteStride is 6 (ATTRIBUTES mode, NONE filter): must be a multiple of 4 in ATTRIBUTES mode "
           "(EXT_meshopt_compression spec, bufferView.EXT_meshopt_compression.byteStride)",
       V::kDoesNotKnowTheExtension},
      {"meshopt_triangles_count_4", meshopt_with({{"mode", "TRIANGLES"}, {"byteStride", 2}}),
       meshopt_at + "count is 4: must be a multiple of 3 in TRIANGLES mode (EXT_meshopt_compression spec, "
                    "bufferView.EXT_meshopt_compression.count)",
       V::kDoesNotKnowTheExtension},
      {"meshopt_fallback_string",
       add_extension("/buffers/0", "EXT_meshopt_compression", {{"fallback", "yes"}}),
       "buffers[0].extensions.EXT_meshopt_compression.fallback is \"yes\": must be true or false "
       "(EXT_meshopt_compression schema, buffer.EXT_meshopt_compression.fallback)",
       V::kDoesNotKnowTheExtension},
      {"instancing_attributes_empty",
       add_extension("/nodes/0", "EXT_mesh_gpu_instancing", {{"attributes", json::object()}}),
       "nodes[0] ('quad').extensions.EXT_mesh_gpu_instancing.attributes is empty: must have at least 1 entry "
       "(EXT_mesh_gpu_instancing schema, node.EXT_mesh_gpu_instancing.attributes)",
       V::kDoesNotKnowTheExtension},
      {"webp_source_negative", add_extension("/textures/0", "EXT_texture_webp", {{"source", -1}}),
       "textures[0].extensions.EXT_texture_webp.source is -1: must be >= 0 (EXT_texture_webp schema, "
       "texture.EXT_texture_webp.source)"},
      {"basisu_source_fraction", add_extension("/textures/0", "KHR_texture_basisu", {{"source", 0.5}}),
       "textures[0].extensions.KHR_texture_basisu.source is 0.5: must be an integer (KHR_texture_basisu "
       "schema, texture.KHR_texture_basisu.source)",
       V::kDoesNotKnowTheExtension},
  };
}

}  // namespace phyir::scenes::test
