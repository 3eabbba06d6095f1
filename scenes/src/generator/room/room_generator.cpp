// generate_room(): a planned room meshed into a glTF document and written with its
// textures.
#include "phyir/scenes/room_generator.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "generator/room/room_primitives.h"
#include "generator/room/room_textures.h"
#include "phyir/core/image_io.h"
#include "phyir/scenes/gltf_writer.h"

namespace phyir::scenes {

namespace fs = std::filesystem;

namespace {

constexpr float kCameraYfov = 1.2f;  // radians, about 69 degrees: a wide indoor view

// Segments around curved parts: enough for smooth glass and metal highlights in hard rooms,
// few in mini rooms, and 8 for cords and handles thinner than 4 cm.
int segments_for(const RoomPart& part, RoomPreset preset) {
  const glm::vec3 s = part.bounds.size();
  if (std::min(s.x, s.z) < 0.04f) return 8;
  return preset == RoomPreset::Hard ? 24 : 16;
}

MeshData part_mesh(const RoomPart& part, RoomPreset preset, float uv_scale) {
  switch (part.shape) {
    case Shape::Cylinder: return cylinder_mesh(part.bounds, segments_for(part, preset), uv_scale);
    case Shape::Sphere: return sphere_mesh(part.bounds, segments_for(part, preset), uv_scale);
    case Shape::Box: break;
  }
  return box_mesh(part.bounds, uv_scale);
}

GltfMaterial to_gltf(const MaterialSpec& m) {
  GltfMaterial g;
  g.name = m.name;
  g.base_color_factor = glm::vec4(m.base_color, 1.0f);
  g.base_color_texture.texture = m.base_color_texture;
  g.metallic_factor = m.metallic;
  g.roughness_factor = m.roughness;
  g.metallic_roughness_texture.texture = m.metallic_roughness_texture;
  g.emissive_factor = m.emissive_factor;
  g.emissive_strength = m.emissive_strength;
  g.transmission_factor = m.transmission;
  if (m.transmission > 0.0f) g.ior = m.ior;
  return g;
}

void add_mesh(GltfDocument& doc, const RoomLayout& layout, const std::string& name, int material, const MeshData& mesh) {
  GltfMesh g;
  g.name = name;
  g.material = material;
  g.positions = mesh.positions;
  g.normals = mesh.normals;
  // Texture coordinates only where a texture reads them (the validator flags unused ones).
  if (layout.materials[material].textured()) g.texcoords0 = mesh.texcoords;
  g.indices = mesh.indices;
  doc.meshes.push_back(std::move(g));
}

void add_shell(GltfDocument& doc, const RoomLayout& layout) {
  const auto repeats = [&](int material) { return layout.materials[material].texture_repeats_per_metre; };
  add_mesh(doc, layout, "floor", layout.floor_material, floor_mesh(layout.shell, repeats(layout.floor_material)));
  add_mesh(doc, layout, "ceiling", layout.ceiling_material, ceiling_mesh(layout.shell, repeats(layout.ceiling_material)));
  // One mesh per wall material, in the order the walls first use them.
  std::vector<int> done;
  for (int material : layout.wall_materials) {
    if (std::find(done.begin(), done.end(), material) != done.end()) continue;
    done.push_back(material);
    MeshData walls;
    for (size_t w = 0; w < layout.wall_materials.size(); ++w) {
      if (layout.wall_materials[w] == material) walls.append(wall_mesh(layout.shell, static_cast<int>(w), repeats(material)));
    }
    add_mesh(doc, layout, "walls_" + layout.materials[material].name, material, walls);
  }
}

// Each object becomes one mesh per material it uses ("table_4_wood"): few nodes, and every
// mesh has one material as the renderer's AOVs expect.
void add_objects(GltfDocument& doc, const RoomLayout& layout) {
  for (size_t k = 0; k < layout.objects.size(); ++k) {
    const RoomObject& object = layout.objects[k];
    std::vector<int> done;
    for (const RoomPart& first : object.parts) {
      if (std::find(done.begin(), done.end(), first.material) != done.end()) continue;
      done.push_back(first.material);
      const MaterialSpec& material = layout.materials[first.material];
      MeshData merged;
      for (const RoomPart& part : object.parts) {
        if (part.material == first.material) merged.append(part_mesh(part, layout.preset, material.texture_repeats_per_metre));
      }
      add_mesh(doc, layout, fmt::format("{}_{}_{}", object.name, k, material.name), first.material, merged);
    }
  }
}

GltfCamera make_camera(const RoomLayout& layout) {
  GltfCamera camera;
  camera.name = "camera";
  camera.position = layout.camera_position;
  camera.yfov = kCameraYfov;
  // A yaw about +Y that turns the camera's -Z onto the (level) view direction.
  const glm::vec3 d = layout.camera_target - layout.camera_position;
  const float yaw = std::atan2(-d.x, -d.z);
  camera.rotation = {0.0f, std::sin(0.5f * yaw), 0.0f, std::cos(0.5f * yaw)};
  return camera;
}

nlohmann::json scene_extras(const RoomLayout& layout) {
  nlohmann::json points = nlohmann::json::array();
  for (const glm::vec3& p : layout.candidate_viewpoints) {
    // Viewpoints sit on a millimetre grid (room_viewpoints.cpp): print them as such.
    points.push_back({std::round(p.x * 1000.0) / 1000.0, std::round(p.y * 1000.0) / 1000.0,
                      std::round(p.z * 1000.0) / 1000.0});
  }
  return {{"phyir",
           {{"candidate_viewpoints", points},
            {"preset", room_preset_name(layout.preset)},
            {"seed", layout.seed},
            {"index", layout.index},
            {"emission_unit", "W/(sr m^2) = emissiveFactor * KHR_materials_emissive_strength"}}}};
}

}  // namespace

RoomSummary generate_room(const fs::path& out_dir, int index, uint64_t seed, RoomPreset preset) {
  const RoomLayout layout = plan_room(seed, index, preset);
  const std::string stem = fmt::format("room_{}", index);
  fs::create_directories(out_dir);

  GltfDocument doc;
  doc.generator = std::string("phyir ") + PHYIR_VERSION;
  for (const TextureSpec& texture : layout.textures) {
    const std::string uri = stem + "_" + texture.name + ".png";
    write_image(out_dir / uri, render_texture(texture));
    doc.textures.push_back({uri, {}, {}});  // written above: the writer only refers to it
  }
  for (const MaterialSpec& m : layout.materials) doc.materials.push_back(to_gltf(m));
  add_shell(doc, layout);
  add_objects(doc, layout);
  doc.cameras.push_back(make_camera(layout));
  doc.scene_extras = scene_extras(layout);
  write_gltf(out_dir / (stem + ".gltf"), doc);

  RoomSummary summary;
  summary.file = stem + ".gltf";
  summary.meshes = doc.meshes.size();
  for (const GltfMesh& m : doc.meshes) {
    summary.triangles += m.indices.size() / 3;
    if (layout.materials[m.material].kind == MaterialKind::Emissive) ++summary.emissive_meshes;
  }
  summary.materials = doc.materials.size();
  summary.textures = doc.textures.size();
  summary.cameras = doc.cameras.size();
  summary.candidate_viewpoints = layout.candidate_viewpoints.size();
  for (int k = 0; k < kMaterialKindCount; ++k) {
    const auto kind = static_cast<MaterialKind>(k);
    const bool present = std::any_of(layout.materials.begin(), layout.materials.end(),
                                     [&](const MaterialSpec& m) { return m.kind == kind; });
    if (present) summary.material_kinds.push_back(material_kind_name(kind));
  }
  return summary;
}

}  // namespace phyir::scenes
