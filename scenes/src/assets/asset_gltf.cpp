#include "phyir/scenes/asset_gltf.h"

#include <fmt/format.h>

namespace phyir::scenes {

namespace {

// ".png" or ".jpg" from the file's first bytes (archives hold both, not always named so).
std::string image_extension(const std::vector<unsigned char>& bytes) {
  return bytes.size() >= 4 && bytes[0] == 0x89 && bytes[1] == 'P' ? ".png" : ".jpg";
}

GltfMaterial gltf_material(const AssetMaterial& a) {
  GltfMaterial g;
  g.name = a.name;
  g.base_color_factor = glm::vec4(a.base_color, a.alpha_mode == AssetAlphaMode::Opaque ? 1.0f : a.alpha);
  g.base_color_texture.texture = a.base_color_texture;  // same indices: one glTF texture per archive image
  g.metallic_factor = a.metallic;
  g.roughness_factor = a.roughness;
  g.transmission_factor = a.transmission;
  if (a.transmission > 0.0f) g.ior = a.ior;
  g.alpha_mode = a.alpha_mode == AssetAlphaMode::Mask    ? AlphaMode::Mask
                 : a.alpha_mode == AssetAlphaMode::Blend ? AlphaMode::Blend
                                                         : AlphaMode::Opaque;
  g.double_sided = a.double_sided;
  return g;
}

}  // namespace

GltfDocument asset_gltf_document(const AssetEntry& entry, const AssetModel& model, const std::string& stem) {
  GltfDocument doc;
  doc.generator = "phyir asset_gltf";
  for (size_t t = 0; t < model.textures.size(); ++t) {
    GltfTexture g;
    g.uri = fmt::format("{}_textures/{}{}", stem, t, image_extension(model.textures[t].bytes));
    g.source.bytes.assign(model.textures[t].bytes.begin(), model.textures[t].bytes.end());
    doc.textures.push_back(std::move(g));
  }
  for (const AssetMaterial& m : model.materials) doc.materials.push_back(gltf_material(m));
  for (size_t k = 0; k < model.meshes.size(); ++k) {
    const AssetMesh& mesh = model.meshes[k];
    GltfMesh g;
    g.name = fmt::format("{}/{}", entry.name, k);
    g.material = mesh.material;
    g.positions = mesh.positions;
    g.normals = mesh.normals;
    // A textured material on a mesh without texture coordinates reads the texture's middle.
    if (doc.materials[size_t(mesh.material)].base_color_texture.present())
      g.texcoords0 = mesh.texcoords.empty() ? std::vector<glm::vec2>(mesh.positions.size(), glm::vec2(0.5f))
                                            : mesh.texcoords;
    g.indices = mesh.indices;
    doc.meshes.push_back(std::move(g));
  }
  doc.scene_extras = {{"asset", {{"name", entry.name}, {"id", entry.id}, {"library", entry.library},
                                 {"creator", entry.creator}, {"licence", entry.licence}}}};
  return doc;
}

void write_asset_gltf(const std::filesystem::path& gltf_path, const AssetEntry& entry, const AssetModel& model) {
  write_gltf(gltf_path, asset_gltf_document(entry, model, gltf_path.stem().string()));
}

}  // namespace phyir::scenes
