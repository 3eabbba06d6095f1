// The apartment's shell as glTF meshes and materials.
#include <fmt/format.h>

#include "generator/apartment/apartment_gltf.h"
#include "generator/apartment/apartment_steps.h"
#include "generator/room/room_materials.h"
#include "generator/room/room_textures.h"
#include "phyir/core/image_io.h"

namespace phyir::scenes {

namespace {

// The room generator's material as a glTF material (textures are renumbered by the caller).
GltfMaterial gltf_material(const MaterialSpec& m, int texture_base) {
  GltfMaterial g;
  g.name = m.name;
  g.base_color_factor = glm::vec4(m.base_color, 1.0f);
  if (m.base_color_texture >= 0) g.base_color_texture.texture = texture_base + m.base_color_texture;
  g.metallic_factor = m.metallic;
  g.roughness_factor = m.roughness;
  if (m.metallic_roughness_texture >= 0) g.metallic_roughness_texture.texture = texture_base + m.metallic_roughness_texture;
  return g;
}

GltfMaterial plain(const std::string& name, glm::vec3 colour, float roughness) {
  GltfMaterial g;
  g.name = name;
  g.base_color_factor = glm::vec4(colour, 1.0f);
  g.metallic_factor = 0.0f;
  g.roughness_factor = roughness;
  return g;
}

MaterialRole role_of(ShellSurface s) {
  switch (s) {
    case ShellSurface::Floor: return MaterialRole::Floor;
    case ShellSurface::Ceiling: return MaterialRole::Ceiling;
    default: return MaterialRole::Wall;
  }
}

}  // namespace

void add_apartment_shell(GltfDocument& doc, const ApartmentPlan& plan, const std::filesystem::path& out_dir,
                         const std::string& stem) {
  // Each room's palette: the hard preset's range (wood planks, tiles, coloured walls).
  std::vector<std::map<MaterialRole, int>> room_materials(plan.rooms.size());
  std::map<int, float> repeats_per_metre;  // by document material
  for (size_t r = 0; r < plan.rooms.size(); ++r) {
    std::vector<MaterialSpec> specs;
    std::vector<TextureSpec> textures;
    Pcg32 rng = apartment_rng(plan.seed, plan.index * 64 + int(r), ApartmentStream::Materials);
    MaterialPalette palette(rng, RoomPreset::Hard, mix64(plan.seed + 977u * r), specs, textures);
    std::map<MaterialRole, int> local;
    for (MaterialRole role : {MaterialRole::Floor, MaterialRole::Wall, MaterialRole::Ceiling}) local[role] = palette.get(role);
    const int texture_base = static_cast<int>(doc.textures.size());
    for (const TextureSpec& t : textures) {
      const std::string uri = fmt::format("{}_{}_{}.png", stem, plan.rooms[r].name, t.name);
      write_image(out_dir / uri, render_texture(t));
      doc.textures.push_back({uri, {}, {}});
    }
    const int material_base = static_cast<int>(doc.materials.size());
    for (const MaterialSpec& spec : specs) {
      GltfMaterial m = gltf_material(spec, texture_base);
      m.name = plan.rooms[r].name + "_" + m.name;
      repeats_per_metre[static_cast<int>(doc.materials.size())] = spec.texture_repeats_per_metre;
      doc.materials.push_back(m);
    }
    for (const auto& [role, index] : local) room_materials[r][role] = material_base + index;
  }
  const int facade = static_cast<int>(doc.materials.size());
  doc.materials.push_back(plain("facade", glm::vec3(0.6f, 0.58f, 0.55f), 0.9f));
  doc.materials.push_back(plain("roof", glm::vec3(0.25f), 0.8f));

  for (const ShellPiece& piece : mesh_apartment_shell(plan)) {
    GltfMesh mesh;
    mesh.positions = piece.positions;
    mesh.normals = piece.normals;
    mesh.indices = piece.indices;
    if (piece.room < 0) {
      mesh.name = shell_surface_name(piece.surface);
      mesh.material = facade + (piece.surface == ShellSurface::Roof ? 1 : 0);
    } else {
      mesh.name = plan.rooms[size_t(piece.room)].name + "_" + shell_surface_name(piece.surface);
      mesh.material = room_materials[size_t(piece.room)].at(role_of(piece.surface));
      const GltfMaterial& m = doc.materials[size_t(mesh.material)];
      if (m.base_color_texture.present() || m.metallic_roughness_texture.present())
        for (const glm::vec2& uv : piece.uvs) mesh.texcoords0.push_back(uv * repeats_per_metre.at(mesh.material));
    }
    doc.meshes.push_back(std::move(mesh));
  }
}

}  // namespace phyir::scenes
