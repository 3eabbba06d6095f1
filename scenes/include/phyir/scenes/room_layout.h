#pragma once
// The plan of a procedural indoor room before it is meshed: shell, materials, textures,
// furniture as axis-aligned parts, camera and candidate viewpoints. plan_room() is a pure
// function of (seed, index, preset), so tests check placement and viewpoints without
// writing files. Units and axes follow scene.h: metres, +Y up, right-handed, floor at y = 0.
#include <glm/glm.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace phyir::scenes {

// mini: small rectangular rooms, one ceiling light, few triangles (fast smoke tests).
// hard: larger rectangular or L-shaped rooms with mirrors, metals, glass, small bright
// lights and thin geometry (the cases that break renderers and the network).
// mini: small and fast; hard: mirrors, metals, glass, small bright lights, thin geometry;
// diffuse: a mini layout whose every non-emissive material is rough (R = 1), non-metallic
// and untextured (the baseline for "simulate only the effects a scene calls for").
enum class RoomPreset { Mini, Hard, Diffuse };

// "mini" or "hard"; throws phyir::Error naming the bad value otherwise.
RoomPreset parse_room_preset(const std::string& name);
const char* room_preset_name(RoomPreset preset);

// The material classes the paper's SVBRDF has to cover.
enum class MaterialKind { Diffuse, Glossy, RoughMetal, PolishedMetal, Mirror, Glass, Emissive };
constexpr int kMaterialKindCount = 7;
// "diffuse", "glossy", "metal_rough", "metal_polished", "mirror", "glass", "emissive".
const char* material_kind_name(MaterialKind kind);

struct Box3 {
  glm::vec3 min{0.0f};
  glm::vec3 max{0.0f};

  glm::vec3 size() const { return max - min; }
  glm::vec3 centre() const { return 0.5f * (min + max); }
  // True when the boxes come closer than `gap` on every axis.
  bool overlaps(const Box3& other, float gap) const;
  // Euclidean distance from p to the box (0 inside).
  float distance_to(const glm::vec3& p) const;
  void extend(const Box3& other);
};

enum class TexturePattern { WoodPlanks, Checker, Tiles, WornMetal };

// A procedural image, written as room_<index>_<name>.png. Colour patterns store sRGB-encoded
// texels (glTF base colour); WornMetal is data: G = roughness, B = metalness (glTF order).
struct TextureSpec {
  std::string name;
  TexturePattern pattern = TexturePattern::Checker;
  int size = 256;                 // square, pixels
  glm::vec3 colour_a{0.8f};       // sRGB-encoded, [0,1]
  glm::vec3 colour_b{0.2f};
  uint64_t seed = 0;
};

// glTF metallic-roughness material plus the KHR extensions the generator uses.
struct MaterialSpec {
  std::string name;
  MaterialKind kind = MaterialKind::Diffuse;
  glm::vec3 base_color{0.8f};  // linear
  float metallic = 0.0f;
  float roughness = 1.0f;
  // Radiance = emissive_factor * emissive_strength in W / (sr m^2); the factor stays in [0,1].
  glm::vec3 emissive_factor{0.0f};
  float emissive_strength = 1.0f;
  float transmission = 0.0f;  // KHR_materials_transmission (glass: 1, with ior 1.5)
  float ior = 1.5f;           // KHR_materials_ior, written for transmissive materials
  int base_color_texture = -1;          // index into RoomLayout::textures
  int metallic_roughness_texture = -1;  // index into RoomLayout::textures
  float texture_repeats_per_metre = 1.0f;

  bool textured() const { return base_color_texture >= 0 || metallic_roughness_texture >= 0; }
};

enum class Shape { Box, Cylinder, Sphere };  // cylinders stand along Y; spheres fill a cube

struct RoomPart {
  std::string name;
  Shape shape = Shape::Box;
  Box3 bounds;
  int material = 0;  // index into RoomLayout::materials
};

enum class Mount { Floor, Wall, Ceiling };

// One piece of furniture, a wall item or a light: parts plus their union box.
struct RoomObject {
  std::string name;
  Mount mount = Mount::Floor;
  std::vector<RoomPart> parts;
  Box3 bounds;
};

// Floor plan: the rectangle x in [-width/2, width/2], z in [-depth/2, depth/2], with the
// notch rectangle removed at the (+x, +z) corner when L-shaped. Walls run floor to ceiling.
struct RoomShell {
  float width = 4.0f;
  float depth = 4.0f;
  float height = 2.6f;
  bool l_shaped = false;
  glm::vec2 notch_min{0.0f};  // (x, z)
  glm::vec2 notch_max{0.0f};

  // Floor polygon corners (x, z) in order; outline()[i] -> outline()[i+1] is wall i.
  std::vector<glm::vec2> outline() const;
  // Index of the corner every floor triangle fans from (the reflex corner of an L).
  int fan_corner() const { return l_shaped ? 3 : 0; }
  // Unit normal of wall i in the floor plane, pointing into the room.
  glm::vec2 wall_inward_normal(int wall) const;
  // Inside the floor polygon with at least `margin` to every wall (conservative at the
  // reflex corner of an L).
  bool contains(glm::vec2 xz, float margin) const;
  bool contains(glm::vec2 min_xz, glm::vec2 max_xz, float margin) const;
};

struct RoomLayout {
  RoomPreset preset = RoomPreset::Mini;
  uint64_t seed = 0;
  int index = 0;
  RoomShell shell;
  int floor_material = 0;
  int ceiling_material = 0;
  std::vector<int> wall_materials;  // one per wall, same order as shell.outline()
  std::vector<MaterialSpec> materials;
  std::vector<TextureSpec> textures;
  std::vector<RoomObject> objects;
  glm::vec3 camera_position{0.0f};
  glm::vec3 camera_target{0.0f};  // the camera looks at it (same height: a level view)
  std::vector<glm::vec3> candidate_viewpoints;
};

// The viewpoint rules, shared by the planner and the tests: 1.2 to 1.8 m above the floor
// (eye heights), at least 0.3 m from every wall and from every object's bounding box (so a
// probe or camera never starts inside or against geometry).
constexpr float kViewpointClearance = 0.3f;
constexpr float kViewpointMinHeight = 1.2f;
constexpr float kViewpointMaxHeight = 1.8f;
constexpr int kMinCandidateViewpoints = 8;

bool is_valid_viewpoint(const RoomLayout& layout, const glm::vec3& p);

RoomLayout plan_room(uint64_t seed, int index, RoomPreset preset);

}  // namespace phyir::scenes
