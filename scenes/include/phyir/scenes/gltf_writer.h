#pragma once
// A small glTF 2.0 writer for generated scenes: world-space meshes (one primitive and one
// node each), metallic-roughness materials with the KHR extensions the toolkit reads,
// external PNG textures and perspective cameras. The JSON goes through nlohmann::json,
// whose sorted keys and own float printing make the text deterministic; geometry goes to
// one little-endian .bin buffer next to it.
#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace phyir::scenes {

struct GltfMesh {
  std::string name;
  int material = -1;                  // index into GltfDocument::materials, -1 = default
  std::vector<glm::vec3> positions;   // world space, metres
  std::vector<glm::vec3> normals;     // unit length, one per position
  std::vector<glm::vec2> texcoords0;  // empty, or one per position
  std::vector<uint32_t> indices;      // triangles, counter-clockwise seen from the front
};

struct GltfMaterial {
  std::string name;
  glm::vec4 base_color_factor{1.0f};     // linear RGBA
  int base_color_texture = -1;           // index into GltfDocument::textures
  float metallic_factor = 1.0f;
  float roughness_factor = 1.0f;
  int metallic_roughness_texture = -1;   // G = roughness, B = metalness
  glm::vec3 emissive_factor{0.0f};       // [0,1]
  float emissive_strength = 1.0f;        // KHR_materials_emissive_strength when != 1
  float transmission_factor = 0.0f;      // KHR_materials_transmission when > 0
  std::optional<float> ior;              // KHR_materials_ior when set
};

// An image file beside the .gltf (relative URI), sampled with REPEAT and trilinear filtering.
struct GltfTexture {
  std::string uri;
};

struct GltfCamera {
  std::string name;
  glm::vec3 position{0.0f};
  glm::vec4 rotation{0.0f, 0.0f, 0.0f, 1.0f};  // unit quaternion (x, y, z, w); looks down -Z
  float yfov = 1.2f;                            // radians
  float znear = 0.01f;                          // no zfar: infinite projection
};

struct GltfDocument {
  std::string generator;  // asset.generator
  std::vector<GltfMesh> meshes;
  std::vector<GltfMaterial> materials;
  std::vector<GltfTexture> textures;
  std::vector<GltfCamera> cameras;
  nlohmann::json scene_extras;  // the scene object's "extras"; null for none
};

struct GltfFiles {
  std::string json;  // the .gltf text
  std::string bin;   // the buffer's bytes
};

// Encodes the document, naming the buffer `bin_uri`. Throws phyir::Error naming the mesh or
// material when the document is inconsistent (index out of range, attribute count mismatch).
GltfFiles encode_gltf(const GltfDocument& document, const std::string& bin_uri);

// Writes <gltf_path> and <stem>.bin beside it, each atomically; the .bin first, so a .gltf
// on disk always has its buffer.
void write_gltf(const std::filesystem::path& gltf_path, const GltfDocument& document);

}  // namespace phyir::scenes
