#pragma once
// The material palette of one room. Materials are created on first use of their role, so
// every material in the file is used by some mesh (the glTF validator flags unused ones) and
// all furniture of a role matches (the legs of every table share one metal).
#include <map>
#include <string>
#include <vector>

#include "generator/room/room_rng.h"
#include "phyir/scenes/room_layout.h"

namespace phyir::scenes {

enum class MaterialRole {
  Wall, AccentWall, Floor, Ceiling,
  Wood,           // furniture wood, textured in hard rooms
  Paint,          // painted furniture (diffuse)
  Fabric,         // rough coloured diffuse (boxes, stools)
  Lacquer,        // glossy dielectric: low roughness, metalness 0
  Ceramic,        // glossy dielectric, white-ish
  RoughMetal, PolishedMetal, WornMetal,  // WornMetal: metallicRoughness texture
  Mirror, Glass,
  Checker,        // checker-textured diffuse
  LightPanel, LampShade, BrightBulb,
};

class MaterialPalette {
 public:
  MaterialPalette(Pcg32 rng, RoomPreset preset, uint64_t texture_seed,
                  std::vector<MaterialSpec>& materials, std::vector<TextureSpec>& textures);

  // Index into the room's materials; creates the material on the first call for a role.
  int get(MaterialRole role);

 private:
  // make() hands each role to its step: the shell (walls, ceiling), the floor, furniture
  // finishes, specular materials (metals, mirror, glass) and lights.
  MaterialSpec make(MaterialRole role);
  MaterialSpec make_shell(MaterialRole role);
  MaterialSpec make_floor();
  MaterialSpec make_furniture(MaterialRole role);
  MaterialSpec make_specular(MaterialRole role);
  MaterialSpec make_light(MaterialRole role);
  MaterialSpec make_diffuse(MaterialRole role);
  int add_texture(const std::string& name, TexturePattern pattern, int size, glm::vec3 a,
                  glm::vec3 b);

  Pcg32 rng_;
  RoomPreset preset_;
  uint64_t texture_seed_;
  std::vector<MaterialSpec>& materials_;
  std::vector<TextureSpec>& textures_;
  std::map<MaterialRole, int> by_role_;
};

}  // namespace phyir::scenes
