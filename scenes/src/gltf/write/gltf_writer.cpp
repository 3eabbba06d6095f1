// glTF 2.0 writing: the document's parts encoded in order (gltf_write_*.cpp), assembled into
// one JSON object, then the side files, the buffer and the JSON written.
#include "phyir/scenes/gltf_writer.h"

#include <algorithm>
#include <cmath>
#include <set>

#include "gltf/read/gltf_geometry.h"
#include "gltf/write/gltf_write_buffer.h"
#include "gltf/write/gltf_write_files.h"
#include "gltf/write/gltf_write_lights.h"
#include "gltf/write/gltf_write_materials.h"
#include "gltf/write/gltf_write_textures.h"
#include "gltf/write/gltf_write_values.h"
#include "phyir/core/atomic_file.h"
#include "phyir/core/error.h"

namespace phyir::scenes {

namespace fs = std::filesystem;
using nlohmann::json;
using namespace gltf_write;

namespace {

void check_mesh(const GltfMesh& m, size_t index, const GltfDocument& doc) {
  const std::string what = "glTF writer: mesh " + std::to_string(index) + " ('" + m.name + "')";
  if (m.positions.empty() || m.indices.empty()) fail("{} has no triangles", what);
  if (m.normals.size() != m.positions.size()) {
    fail("{} has {} normals for {} positions", what, m.normals.size(), m.positions.size());
  }
  if (!m.texcoords0.empty() && m.texcoords0.size() != m.positions.size()) {
    fail("{} has {} texture coordinates for {} positions", what, m.texcoords0.size(), m.positions.size());
  }
  if (m.indices.size() % 3 != 0) fail("{} has {} indices, not a multiple of 3", what, m.indices.size());
  const uint32_t largest = *std::max_element(m.indices.begin(), m.indices.end());
  if (largest >= m.positions.size()) fail("{} index {} is past its {} vertices", what, largest, m.positions.size());
  if (m.material >= static_cast<int>(doc.materials.size())) {
    fail("{} uses material {} of {}", what, m.material, doc.materials.size());
  }
  if (m.material >= 0 && m.texcoords0.empty() && uses_textures(doc.materials[static_cast<size_t>(m.material)]))
    fail("{} has no texture coordinates but its material '{}' has textures", what,
         doc.materials[static_cast<size_t>(m.material)].name);
  if (!m.extras.is_null() && !m.extras.is_object()) fail("{} extras must be a JSON object", what);
}

const GltfMaterial* material_of(const GltfMesh& m, const GltfDocument& doc) {
  return m.material >= 0 ? &doc.materials[static_cast<size_t>(m.material)] : nullptr;
}

// The tangents the loader would derive (gltf_geometry.h), written so that viewers need not
// generate their own (the validator warns that those are not portable).
std::vector<glm::vec4> tangents_for(const GltfMesh& m) {
  Mesh mesh;
  mesh.positions = m.positions;
  mesh.normals = m.normals;
  mesh.texcoords0 = m.texcoords0;
  for (size_t t = 0; t + 2 < m.indices.size(); t += 3)
    mesh.triangles.emplace_back(m.indices[t], m.indices[t + 1], m.indices[t + 2]);
  gltf::generate_tangents(mesh, 0);
  return mesh.tangents;
}

// POSITION and NORMAL; TEXCOORD_0 only where a texture reads it (the validator flags unused
// ones) and TANGENT where a normal map needs it.
json encode_attributes(const GltfMesh& m, const GltfMaterial* material, BufferEncoder& buffer) {
  json attributes = {{"POSITION", buffer.add_vectors(m.positions, true)},
                     {"NORMAL", buffer.add_vectors(m.normals, false)}};
  const bool textured = material != nullptr && uses_textures(*material);
  if (textured) attributes["TEXCOORD_0"] = buffer.add_vectors(m.texcoords0, false);
  if (textured && material->normal_texture.present()) attributes["TANGENT"] = buffer.add_vectors(tangents_for(m), false);
  return attributes;
}

// The meshes, each on a node of its own.
json encode_meshes(const GltfDocument& doc, BufferEncoder& buffer, json& nodes, json& scene_nodes) {
  json meshes = json::array();
  for (size_t i = 0; i < doc.meshes.size(); ++i) {
    const GltfMesh& m = doc.meshes[i];
    check_mesh(m, i, doc);
    const json attributes = encode_attributes(m, material_of(m, doc), buffer);
    json primitive = {{"attributes", attributes}, {"indices", buffer.add_indices(m.indices)}};
    if (m.material >= 0) primitive["material"] = m.material;
    meshes.push_back({{"name", m.name}, {"primitives", json::array({primitive})}});
    scene_nodes.push_back(nodes.size());
    json node = {{"name", m.name}, {"mesh", i}};
    if (!m.extras.is_null()) node["extras"] = m.extras;
    nodes.push_back(std::move(node));
  }
  return meshes;
}

json encode_cameras(const GltfDocument& doc, json& nodes, json& scene_nodes) {
  json cameras = json::array();
  for (size_t i = 0; i < doc.cameras.size(); ++i) {
    const GltfCamera& c = doc.cameras[i];
    cameras.push_back({{"name", c.name},
                       {"type", "perspective"},
                       {"perspective", {{"yfov", tidy(c.yfov)}, {"znear", tidy(c.znear)}}}});
    scene_nodes.push_back(nodes.size());
    nodes.push_back({{"name", c.name},
                     {"camera", i},
                     {"translation", tidy_array(&c.position[0], 3)},
                     {"rotation", tidy_array(&c.rotation[0], 4)}});
  }
  return cameras;
}

// The scene's extras: the document's, plus phyir.environment when it has one.
json scene_extras(const GltfDocument& doc, std::vector<GltfSideFile>& side_files) {
  json extras = doc.scene_extras;
  if (!extras.is_null() && !extras.is_object()) fail("glTF writer: scene_extras must be a JSON object");
  if (!doc.environment) return extras;
  const GltfEnvironment& env = *doc.environment;
  check_side_uri(env.uri, "environment");
  check_source(env.source, "environment");
  if (!(env.scale >= 0.0f) || !std::isfinite(env.scale))
    fail("glTF writer: environment scale is {}: must be a finite number >= 0", env.scale);
  json& phyir = extras["phyir"];
  if (!phyir.is_null() && !phyir.is_object()) fail("glTF writer: scene_extras.phyir must be a JSON object");
  if (phyir.contains("environment"))
    fail("glTF writer: scene_extras.phyir.environment is set and so is the document's environment: give one");
  phyir["environment"] = {{"uri", env.uri}, {"scale", exact(env.scale)}};
  if (!env.source.empty()) side_files.push_back({env.uri, env.source});
  return extras;
}

// The buffer, the images (already one per uri) and the environment each need a file of their own.
void check_unique_uris(const GltfDocument& doc, const json& images, const std::string& bin_uri) {
  std::set<std::string> seen{bin_uri};
  const auto add = [&](const std::string& uri) {
    if (!seen.insert(uri).second) fail("glTF writer: two files would be written as '{}'", uri);
  };
  for (const json& image : images) add(image["uri"].get<std::string>());
  if (doc.environment) add(doc.environment->uri);
}

}  // namespace

GltfFiles encode_gltf(const GltfDocument& doc, const std::string& bin_uri) {
  json root;
  root["asset"] = {{"version", "2.0"}, {"generator", doc.generator}};

  BufferEncoder buffer;
  json nodes = json::array(), scene_nodes = json::array();
  const json meshes = encode_meshes(doc, buffer, nodes, scene_nodes);
  const json cameras = encode_cameras(doc, nodes, scene_nodes);
  const json lights = encode_lights(doc.lights, nodes, scene_nodes);

  std::set<std::string> extensions;
  json materials = json::array();
  for (const GltfMaterial& m : doc.materials) materials.push_back(encode_material(m, doc, extensions));
  EncodedTextures textures = encode_textures(doc.textures);

  json scene = {{"name", "room"}, {"nodes", scene_nodes}};
  const json extras = scene_extras(doc, textures.side_files);
  if (!extras.is_null()) scene["extras"] = extras;
  root["scene"] = 0;
  root["scenes"] = json::array({scene});
  root["nodes"] = nodes;
  if (!meshes.empty()) root["meshes"] = meshes;
  if (!materials.empty()) root["materials"] = materials;
  if (!cameras.empty()) root["cameras"] = cameras;
  if (!doc.textures.empty()) {
    root["images"] = textures.images;
    root["textures"] = textures.textures;
    root["samplers"] = textures.samplers;
  }
  if (!buffer.bytes().empty()) {
    root["buffers"] = json::array({{{"uri", bin_uri}, {"byteLength", buffer.bytes().size()}}});
    root["bufferViews"] = buffer.views();
    root["accessors"] = buffer.accessors();
  }
  if (!lights.empty()) {
    // Required as Blender's exporter writes it: a viewer without lights would show another scene.
    root["extensions"] = {{"KHR_lights_punctual", {{"lights", lights}}}};
    root["extensionsRequired"] = json::array({"KHR_lights_punctual"});
    extensions.insert("KHR_lights_punctual");
  }
  if (!extensions.empty()) root["extensionsUsed"] = json(std::vector<std::string>(extensions.begin(), extensions.end()));
  check_unique_uris(doc, textures.images, bin_uri);

  return {root.dump(2) + "\n", buffer.bytes(), std::move(textures.side_files)};
}

void write_gltf(const fs::path& gltf_path, const GltfDocument& document) {
  const std::string bin_name = gltf_path.stem().string() + ".bin";
  const GltfFiles files = encode_gltf(document, bin_name);
  for (const GltfSideFile& f : files.side_files) write_side_file(gltf_path.parent_path(), f);
  write_file_atomic(gltf_path.parent_path() / bin_name, files.bin);
  write_file_atomic(gltf_path, files.json);
}

}  // namespace phyir::scenes
