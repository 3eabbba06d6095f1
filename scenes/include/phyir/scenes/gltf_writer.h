#pragma once
// A small glTF 2.0 writer for generated scenes: world-space meshes (one primitive and one
// node each, the node with optional extras), metallic-roughness materials with the KHR
// extensions the toolkit reads, textures (JPEG or PNG files beside the .gltf, copied from
// a file or from memory, with their sampler and KHR_texture_transform), perspective
// cameras, KHR_lights_punctual lights and an equirect environment declared in the scene's
// extras (docs/gltf-support.md#writing). The JSON goes through nlohmann::json, whose
// sorted keys and own float printing make the text deterministic; geometry goes to one
// little-endian .bin buffer next to it.
#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "phyir/scenes/scene.h"

namespace phyir::scenes {

struct GltfMesh {
  std::string name;                   // the mesh's and its node's name
  int material = -1;                  // index into GltfDocument::materials, -1 = default
  std::vector<glm::vec3> positions;   // world space, metres
  std::vector<glm::vec3> normals;     // unit length, one per position
  std::vector<glm::vec2> texcoords0;  // empty, or one per position; written when the material has
                                      // textures (then required), with tangents for a normal map
  std::vector<uint32_t> indices;      // triangles, counter-clockwise seen from the front
  nlohmann::json extras;              // the node's "extras" (an asset's name, library, creator, licence); null for none
};

// A material's use of a texture (glTF textureInfo), read through TEXCOORD_0.
struct GltfTextureRef {
  int texture = -1;                           // index into GltfDocument::textures; -1 = none
  std::optional<TextureTransform> transform;  // KHR_texture_transform when set and not the identity
  bool present() const { return texture >= 0; }
};

struct GltfMaterial {
  std::string name;
  glm::vec4 base_color_factor{1.0f};     // linear RGBA
  GltfTextureRef base_color_texture;     // sRGB
  float metallic_factor = 1.0f;
  float roughness_factor = 1.0f;
  GltfTextureRef metallic_roughness_texture;  // G = roughness, B = metalness
  GltfTextureRef normal_texture;         // tangent space (the loader derives tangents from the UVs)
  float normal_scale = 1.0f;
  glm::vec3 emissive_factor{0.0f};       // [0,1]
  GltfTextureRef emissive_texture;       // sRGB, multiplies emissive_factor
  float emissive_strength = 1.0f;        // KHR_materials_emissive_strength when != 1
  float transmission_factor = 0.0f;      // KHR_materials_transmission when > 0
  std::optional<float> ior;              // KHR_materials_ior when set
  AlphaMode alpha_mode = AlphaMode::Opaque;
  float alpha_cutoff = 0.5f;             // written for Mask only
  bool double_sided = false;
};

// Where the writer gets a file it puts beside the .gltf: copied from `file`, or `bytes`
// written as they are (the bytes when both are set). With neither, the caller has written
// the file itself and the writer only refers to it.
struct GltfFileSource {
  std::filesystem::path file;
  std::string bytes;
  bool empty() const { return file.empty() && bytes.empty(); }
};

enum class GltfWrap { Repeat, ClampToEdge, MirroredRepeat };

// Always linear magnification and trilinear minification; the wrap modes vary.
struct GltfSampler {
  GltfWrap wrap_s = GltfWrap::Repeat;
  GltfWrap wrap_t = GltfWrap::Repeat;
  bool operator==(const GltfSampler& o) const { return wrap_s == o.wrap_s && wrap_t == o.wrap_t; }
};

// A PNG or JPEG image beside the .gltf under `uri` (a relative path of letters, digits, '.',
// '_', '-' and '/'), and the sampler that reads it. With a source, the writer checks the
// bytes are PNG or JPEG (matching the uri's extension), writes the image's mimeType and
// copies the file; textures that share a uri share one image.
struct GltfTexture {
  std::string uri;
  GltfFileSource source;
  GltfSampler sampler;
};

struct GltfCamera {
  std::string name;
  glm::vec3 position{0.0f};
  glm::vec4 rotation{0.0f, 0.0f, 0.0f, 1.0f};  // unit quaternion (x, y, z, w); looks down -Z
  float yfov = 1.2f;                            // radians
  float znear = 0.01f;                          // no zfar: infinite projection
};

// A KHR_lights_punctual light on a node of its own. Intensities are glTF's photometric
// ones; a generator working in the toolkit's radiometric units (W/sr, W/m^2) converts with
// set_radiometric (683 lm/W, docs/conventions.md#lights), which the loader inverts.
struct GltfLight {
  std::string name;
  PunctualLight::Type type = PunctualLight::Type::Point;
  glm::vec3 color{1.0f};                // linear RGB in [0, 1]
  float intensity = 1.0f;               // candela (point, spot) or lux (directional)
  glm::vec3 position{0.0f};             // the node's translation, metres
  glm::vec3 direction{0.0f, 0.0f, -1.0f};  // where the light shines (spot, directional): the node's -Z
  float inner_cone_angle = 0.0f;        // radians (spot); < outer_cone_angle
  float outer_cone_angle = 0.7853982f;  // radians (spot); in (0, pi/2]
  std::optional<float> range;           // metres; the toolkit ignores it
  nlohmann::json extras;                // the node's "extras"; null for none

  // Sets colour and intensity so that the light's radiometric value (PunctualLight::
  // radiometric(): W/sr for point and spot, W/m^2 for directional) is `rgb`: intensity =
  // 683 x the largest channel, colour = rgb / that channel.
  void set_radiometric(const glm::vec3& rgb);
};

// An HDR equirectangular environment (EXR or Radiance HDR in the toolkit's equirect
// mapping) beside the .gltf, declared as the scene's extras.phyir.environment
// (docs/gltf-support.md#environment). `scale` multiplies its radiance.
struct GltfEnvironment {
  std::string uri;
  GltfFileSource source;
  float scale = 1.0f;
};

struct GltfDocument {
  std::string generator;  // asset.generator
  std::vector<GltfMesh> meshes;
  std::vector<GltfMaterial> materials;
  std::vector<GltfTexture> textures;
  std::vector<GltfCamera> cameras;
  std::vector<GltfLight> lights;
  std::optional<GltfEnvironment> environment;
  nlohmann::json scene_extras;  // the scene object's "extras" (an object or null)
};

// A file the writer puts beside the .gltf.
struct GltfSideFile {
  std::string uri;
  GltfFileSource source;
};

struct GltfFiles {
  std::string json;                     // the .gltf text
  std::string bin;                      // the buffer's bytes
  std::vector<GltfSideFile> side_files;  // images and environment with a source, each uri once
};

// Encodes the document, naming the buffer `bin_uri`. Reads the first bytes of source files
// (to name their type). Throws phyir::Error naming the mesh, material, texture or light
// when the document is inconsistent (index out of range, attribute count mismatch, a
// texture that is neither PNG nor JPEG, a light value glTF forbids).
GltfFiles encode_gltf(const GltfDocument& document, const std::string& bin_uri);

// Writes the side files, then <stem>.bin, then <gltf_path>, each atomically (temporary
// name, then rename), so a .gltf on disk always has its buffer and images. The same
// document gives the same bytes.
void write_gltf(const std::filesystem::path& gltf_path, const GltfDocument& document);

}  // namespace phyir::scenes
