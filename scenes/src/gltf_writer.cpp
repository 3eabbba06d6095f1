// glTF 2.0 writing: JSON via nlohmann::json, geometry in one little-endian buffer with one
// tightly packed buffer view per accessor (views shared between vertex attributes would
// need byteStride).
#include "phyir/scenes/gltf_writer.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <set>

#include "phyir/core/atomic_file.h"
#include "phyir/core/error.h"

namespace phyir::scenes {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// glTF enums (specification section 5).
constexpr int kArrayBuffer = 34962;
constexpr int kElementArrayBuffer = 34963;
constexpr int kComponentFloat = 5126;
constexpr int kComponentUnsignedInt = 5125;
constexpr int kFilterLinear = 9729;
constexpr int kFilterLinearMipmapLinear = 9987;
constexpr int kWrapRepeat = 10497;

// Factors rounded to 6 decimals print short ("0.35", not 0.3499999940395355); a millionth
// is far below what 8-bit textures or renderers resolve.
double tidy(float v) { return std::round(static_cast<double>(v) * 1e6) / 1e6; }

json tidy_array(const float* v, int n) {
  json a = json::array();
  for (int i = 0; i < n; ++i) a.push_back(tidy(v[i]));
  return a;
}

// The .bin buffer and the views and accessors into it.
class BufferEncoder {
 public:
  template <int N>
  int add_vectors(const std::vector<glm::vec<N, float>>& data, bool with_bounds) {
    const size_t offset = bin_.size();
    glm::vec<N, float> lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
    for (const auto& v : data) {
      for (int c = 0; c < N; ++c) put_float(v[c]);
      lo = glm::min(lo, v);
      hi = glm::max(hi, v);
    }
    json accessor = {{"bufferView", add_view(offset, kArrayBuffer)},
                     {"componentType", kComponentFloat},
                     {"count", data.size()},
                     {"type", N == 2 ? "VEC2" : "VEC3"}};
    if (with_bounds) {
      // Exact float values: the validator compares them with the buffer's contents.
      json min = json::array(), max = json::array();
      for (int c = 0; c < N; ++c) {
        min.push_back(static_cast<double>(lo[c]));
        max.push_back(static_cast<double>(hi[c]));
      }
      accessor["min"] = min;
      accessor["max"] = max;
    }
    return add_accessor(std::move(accessor));
  }

  int add_indices(const std::vector<uint32_t>& indices) {
    const size_t offset = bin_.size();
    for (uint32_t i : indices) put_u32(i);
    return add_accessor({{"bufferView", add_view(offset, kElementArrayBuffer)},
                         {"componentType", kComponentUnsignedInt},
                         {"count", indices.size()},
                         {"type", "SCALAR"}});
  }

  const std::string& bytes() const { return bin_; }
  json views() const { return views_; }
  json accessors() const { return accessors_; }

 private:
  // Little-endian whatever the host: the file must not depend on the machine.
  void put_u32(uint32_t w) {
    for (int b = 0; b < 4; ++b) bin_.push_back(static_cast<char>((w >> (8 * b)) & 0xFFu));
  }
  void put_float(float f) {
    uint32_t w;
    std::memcpy(&w, &f, sizeof w);
    put_u32(w);
  }
  int add_view(size_t offset, int target) {
    views_.push_back({{"buffer", 0}, {"byteOffset", offset}, {"byteLength", bin_.size() - offset}, {"target", target}});
    return static_cast<int>(views_.size()) - 1;
  }
  int add_accessor(json accessor) {
    accessors_.push_back(std::move(accessor));
    return static_cast<int>(accessors_.size()) - 1;
  }

  std::string bin_;
  json views_ = json::array();
  json accessors_ = json::array();
};

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
}

json texture_ref(int texture, const GltfDocument& doc, const std::string& material) {
  if (texture >= static_cast<int>(doc.textures.size())) {
    fail("glTF writer: material '{}' uses texture {} of {}", material, texture, doc.textures.size());
  }
  return {{"index", texture}};
}

json encode_material(const GltfMaterial& m, const GltfDocument& doc, std::set<std::string>& extensions) {
  json pbr = {{"baseColorFactor", tidy_array(&m.base_color_factor[0], 4)},
              {"metallicFactor", tidy(m.metallic_factor)},
              {"roughnessFactor", tidy(m.roughness_factor)}};
  if (m.base_color_texture >= 0) pbr["baseColorTexture"] = texture_ref(m.base_color_texture, doc, m.name);
  if (m.metallic_roughness_texture >= 0) {
    pbr["metallicRoughnessTexture"] = texture_ref(m.metallic_roughness_texture, doc, m.name);
  }
  json out = {{"name", m.name}, {"pbrMetallicRoughness", pbr}};
  if (m.emissive_factor != glm::vec3(0.0f)) out["emissiveFactor"] = tidy_array(&m.emissive_factor[0], 3);
  json ext = json::object();
  if (m.emissive_strength != 1.0f) {
    ext["KHR_materials_emissive_strength"] = {{"emissiveStrength", tidy(m.emissive_strength)}};
  }
  if (m.transmission_factor > 0.0f) {
    ext["KHR_materials_transmission"] = {{"transmissionFactor", tidy(m.transmission_factor)}};
  }
  if (m.ior) ext["KHR_materials_ior"] = {{"ior", tidy(*m.ior)}};
  for (const auto& item : ext.items()) extensions.insert(item.key());
  if (!ext.empty()) out["extensions"] = ext;
  return out;
}

}  // namespace

GltfFiles encode_gltf(const GltfDocument& doc, const std::string& bin_uri) {
  json root;
  root["asset"] = {{"version", "2.0"}, {"generator", doc.generator}};

  BufferEncoder buffer;
  json meshes = json::array(), nodes = json::array(), scene_nodes = json::array();
  for (size_t i = 0; i < doc.meshes.size(); ++i) {
    const GltfMesh& m = doc.meshes[i];
    check_mesh(m, i, doc);
    json attributes = {{"POSITION", buffer.add_vectors(m.positions, true)},
                       {"NORMAL", buffer.add_vectors(m.normals, false)}};
    if (!m.texcoords0.empty()) attributes["TEXCOORD_0"] = buffer.add_vectors(m.texcoords0, false);
    json primitive = {{"attributes", attributes}, {"indices", buffer.add_indices(m.indices)}};
    if (m.material >= 0) primitive["material"] = m.material;
    meshes.push_back({{"name", m.name}, {"primitives", json::array({primitive})}});
    scene_nodes.push_back(nodes.size());
    nodes.push_back({{"name", m.name}, {"mesh", i}});
  }

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

  std::set<std::string> extensions;
  json materials = json::array();
  for (const GltfMaterial& m : doc.materials) materials.push_back(encode_material(m, doc, extensions));

  json scene = {{"name", "room"}, {"nodes", scene_nodes}};
  if (!doc.scene_extras.is_null()) scene["extras"] = doc.scene_extras;
  root["scene"] = 0;
  root["scenes"] = json::array({scene});
  root["nodes"] = nodes;
  if (!meshes.empty()) root["meshes"] = meshes;
  if (!materials.empty()) root["materials"] = materials;
  if (!cameras.empty()) root["cameras"] = cameras;
  if (!doc.textures.empty()) {
    json images = json::array(), textures = json::array();
    for (size_t i = 0; i < doc.textures.size(); ++i) {
      images.push_back({{"uri", doc.textures[i].uri}});
      textures.push_back({{"sampler", 0}, {"source", i}});
    }
    root["images"] = images;
    root["textures"] = textures;
    root["samplers"] = json::array({{{"magFilter", kFilterLinear},
                                     {"minFilter", kFilterLinearMipmapLinear},
                                     {"wrapS", kWrapRepeat},
                                     {"wrapT", kWrapRepeat}}});
  }
  if (!buffer.bytes().empty()) {
    root["buffers"] = json::array({{{"uri", bin_uri}, {"byteLength", buffer.bytes().size()}}});
    root["bufferViews"] = buffer.views();
    root["accessors"] = buffer.accessors();
  }
  if (!extensions.empty()) root["extensionsUsed"] = json(std::vector<std::string>(extensions.begin(), extensions.end()));

  return {root.dump(2) + "\n", buffer.bytes()};
}

void write_gltf(const fs::path& gltf_path, const GltfDocument& document) {
  const std::string bin_name = gltf_path.stem().string() + ".bin";
  const GltfFiles files = encode_gltf(document, bin_name);
  write_file_atomic(gltf_path.parent_path() / bin_name, files.bin);
  write_file_atomic(gltf_path, files.json);
}

}  // namespace phyir::scenes
