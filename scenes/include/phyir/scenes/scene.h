#pragma once
// The toolkit's scene: what the glTF loader produces and the renderer consumes.
// Conventions (docs/conventions.md): metres, right-handed, +Y up, glTF's -Z forward
// for cameras. Geometry is baked to world space; triangles wind counter-clockwise
// seen from the side the geometric normal points to.
#include <glm/glm.hpp>

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "phyir/scenes/texture.h"

namespace phyir::scenes {

enum class AlphaMode { Opaque, Mask, Blend };

// glTF KHR_texture_transform, applied as uv' = T * R * S * uv (the extension's order).
struct TextureTransform {
  glm::vec2 offset{0.0f};
  glm::vec2 scale{1.0f};
  float rotation = 0.0f;  // radians, counter-clockwise in UV space
  bool is_identity() const {
    return offset == glm::vec2(0.0f) && scale == glm::vec2(1.0f) && rotation == 0.0f;
  }
  glm::vec2 apply(glm::vec2 uv) const;
};

// A material's use of a texture. texture < 0 means "no texture".
struct TextureSlot {
  int texture = -1;
  int texcoord = 0;  // which TEXCOORD_n set
  TextureTransform transform;
  bool present() const { return texture >= 0; }
};

// glTF pbrMetallicRoughness plus the extensions the renderer understands. Factors
// multiply texture values, as in the glTF specification.
struct Material {
  std::string name;
  glm::vec4 base_color_factor{1.0f};  // linear RGBA
  TextureSlot base_color_texture;     // sRGB-decoded
  float metallic_factor = 1.0f;
  float roughness_factor = 1.0f;
  TextureSlot metallic_roughness_texture;  // linear; G = roughness, B = metalness
  TextureSlot normal_texture;              // tangent-space, linear
  float normal_scale = 1.0f;
  glm::vec3 emissive_factor{0.0f};  // linear RGB
  float emissive_strength = 1.0f;   // KHR_materials_emissive_strength
  TextureSlot emissive_texture;     // sRGB-decoded
  float transmission_factor = 0.0f; // KHR_materials_transmission
  TextureSlot transmission_texture; // linear; R channel
  float ior = 1.5f;                 // KHR_materials_ior
  AlphaMode alpha_mode = AlphaMode::Opaque;
  float alpha_cutoff = 0.5f;
  bool double_sided = false;
  std::vector<std::string> extensions;  // the KHR_* extensions this material used

  // Radiance scale of the emission: emissive_factor * emissive_strength (W / (sr m^2)
  // in the toolkit's units; glTF leaves the unit open).
  glm::vec3 emission() const { return emissive_factor * emissive_strength; }
  bool is_emissive() const {
    const glm::vec3 e = emission();
    return e.x > 0.0f || e.y > 0.0f || e.z > 0.0f;
  }
  bool is_transmissive() const { return transmission_factor > 0.0f || transmission_texture.present(); }
  bool is_textured() const {
    return base_color_texture.present() || metallic_roughness_texture.present() ||
           normal_texture.present() || emissive_texture.present() || transmission_texture.present();
  }
};

// One glTF primitive instance, baked to world space. Attribute arrays are either empty
// or have one entry per position.
struct Mesh {
  std::string name;  // "<mesh name>/<primitive index>" of the source file
  int material = 0;  // index into Scene::materials (the loader adds a default material)
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;     // unit, world space; generated when absent
  std::vector<glm::vec4> tangents;    // xyz unit, w = handedness; may be empty
  std::vector<glm::vec2> texcoords0;  // may be empty
  std::vector<glm::vec2> texcoords1;  // may be empty
  std::vector<glm::vec4> colors;      // COLOR_0, linear RGBA; may be empty
  std::vector<glm::uvec3> triangles;  // indices into the attribute arrays
};

struct Camera {
  std::string name;
  glm::vec3 position{0.0f};
  glm::vec3 forward{0.0f, 0.0f, -1.0f};  // the node's -Z axis in world space
  glm::vec3 up{0.0f, 1.0f, 0.0f};        // the node's +Y axis in world space
  bool perspective = true;
  float yfov = 0.8f;           // radians (perspective)
  float aspect_ratio = 0.0f;   // 0 = unspecified
  float znear = 0.01f;
  float zfar = 0.0f;           // 0 = infinite
};

// A KHR_lights_punctual light, placed in world space. glTF gives photometric units; the
// toolkit renders radiometric ones, converted with 683 lm/W as Blender's glTF importer and
// exporter do (docs/conventions.md#lights), so a scene keeps its brightness through Blender.
struct PunctualLight {
  enum class Type { Point, Spot, Directional };
  static constexpr float kLumensPerWatt = 683.0f;

  std::string name;
  Type type = Type::Point;
  glm::vec3 color{1.0f};     // linear RGB
  float intensity = 1.0f;    // as in the file: candela (point, spot) or lux (directional)
  glm::vec3 position{0.0f};  // world space (point, spot)
  glm::vec3 direction{0.0f, 0.0f, -1.0f};  // unit, where the light travels: the node's -Z (spot, directional)
  float inner_cone_angle = 0.0f;           // radians (spot)
  float outer_cone_angle = 0.7853982f;     // radians (spot)
  float range = 0.0f;                      // from the file; 0 = unlimited. Not used (docs/gltf-support.md)

  // Point and spot: radiant intensity in W/sr (per colour channel) on the light's axis.
  // Directional: irradiance in W/m^2 on a surface facing it.
  glm::vec3 radiometric() const { return color * (intensity / kLumensPerWatt); }
  // The spot cone's falloff for a direction whose cosine with `direction` is `cos_angle`:
  // 1 inside the inner cone, 0 outside the outer, the extension's quadratic ramp between.
  float spot_falloff(float cos_angle) const;
};

const char* to_string(PunctualLight::Type type);

// An HDR equirectangular environment the scene declares in its extras.phyir.environment
// (docs/gltf-support.md#environment): the map in the toolkit's equirect mapping, world-aligned,
// its radiance times `scale`. The loader checks the file exists; the renderer decodes it.
struct SceneEnvironment {
  std::string uri;             // as written in the file
  std::filesystem::path path;  // resolved relative to the .gltf
  float scale = 1.0f;
};

// A light portal: an opening (a window) through which the environment lights the interior,
// the parallelogram corner + a edge_u + b edge_v (a, b in [0, 1]), edge_u x edge_v pointing
// into the interior. Renderers sample the environment through it (environment_portals.h);
// it is not geometry (docs/gltf-support.md#light-portals).
struct Portal {
  glm::vec3 corner{0.0f}, edge_u{0.0f}, edge_v{0.0f};
};

struct Bounds {
  glm::vec3 min{1e30f};
  glm::vec3 max{-1e30f};
  bool empty() const { return min.x > max.x; }
  void extend(const glm::vec3& p) {
    min = glm::min(min, p);
    max = glm::max(max, p);
  }
};

// What the source file declared, for `phyir scenes info` and loader tests. Counts are the
// lengths of the file's top-level arrays, before any baking.
struct SourceInfo {
  int nodes = 0;
  int meshes = 0;
  int primitives = 0;       // summed over meshes
  int mesh_instances = 0;   // mesh nodes reached from the default scene
  int gpu_instances = 0;    // EXT_mesh_gpu_instancing copies drawn, summed over those nodes
  size_t unique_triangles = 0;  // of the primitives drawn, each counted once (before any instancing)
  int materials = 0;
  int textures = 0;
  int images = 0;
  int samplers = 0;
  int cameras = 0;
  int lights = 0;           // KHR_lights_punctual lights declared
  int default_scene = 0;
  std::vector<std::string> extensions_used;
  std::vector<std::string> extensions_required;
  std::string generator;    // asset.generator
};

struct Scene {
  std::string source;  // the file it came from
  SourceInfo info;
  std::vector<Mesh> meshes;
  std::vector<Material> materials;
  std::vector<Texture> textures;
  std::vector<Camera> cameras;
  std::vector<PunctualLight> lights;  // one per light-carrying node of the default scene
  // Further valid viewpoints (world space), from the scene's extras.phyir.candidate_viewpoints.
  std::vector<glm::vec3> candidate_viewpoints;
  std::optional<SceneEnvironment> environment;  // from the scene's extras.phyir.environment
  std::vector<Portal> portals;  // from the scene's extras.phyir.portals
  Bounds bounds;
  std::vector<std::string> warnings;  // everything the loader skipped or approximated

  size_t triangle_count() const;
  Bounds compute_bounds() const;
};

}  // namespace phyir::scenes
