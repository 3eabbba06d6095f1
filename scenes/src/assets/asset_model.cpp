// load_model: archive -> OBJ soup -> normalised frame -> meshes and PBR materials.
#include "phyir/scenes/asset_model.h"

#include <algorithm>
#include <limits>

#include "assets/asset_meshes.h"
#include "assets/asset_normalise.h"
#include "assets/asset_obj.h"
#include "assets/asset_textures.h"
#include "assets/asset_zip.h"
#include "phyir/core/error.h"

namespace phyir::scenes {

namespace {

AssetMaterial material_with_textures(const MtlMaterial& mtl, TextureFiles& files, const std::vector<AssetTexture>& textures,
                                     std::vector<std::string>& warnings) {
  const int base = files.find(mtl.map_Kd, mtl.map_Kd_raw);
  const int alpha = files.find(mtl.map_d, mtl.map_d_raw);
  if (base < 0 && !mtl.map_Kd_raw.empty()) {
    warnings.push_back("material '" + mtl.name + "': map_Kd '" + mtl.map_Kd_raw + "' not in the archive: Kd used");
  }
  if (alpha < 0 && !mtl.map_d_raw.empty()) {
    warnings.push_back("material '" + mtl.name + "': map_d '" + mtl.map_d_raw + "' not in the archive: ignored");
  }
  AssetMaterial material = metal_roughness_from_mtl(mtl, base >= 0, alpha >= 0);
  material.base_color_texture = base;
  material.alpha_texture = alpha;
  // Cut-outs (leaves, fences, lace) are PNGs with alpha: coverage, tested against 0.5.
  if (base >= 0 && textures[static_cast<size_t>(base)].has_alpha && material.alpha_mode == AssetAlphaMode::Opaque) {
    material.alpha_mode = AssetAlphaMode::Mask;
  }
  return material;
}

// Materials the meshes use, in mesh order, with the meshes' indices remapped.
void add_used_materials(const ObjSoup& soup, const ZipArchive& zip, AssetModel& model) {
  TextureFiles files(zip, soup.mtl_folder, model.textures);
  for (AssetMesh& mesh : model.meshes) {
    const MtlMaterial& mtl = soup.materials[static_cast<size_t>(mesh.material)];
    model.materials.push_back(material_with_textures(mtl, files, model.textures, model.warnings));
    mesh.material = static_cast<int>(model.materials.size()) - 1;
  }
}

AssetModel load_checked(const AssetEntry& entry, const std::string& context) {
  const ZipArchive zip(entry.archive);
  if (!zip.contains(entry.model_path)) fail("{}: no such file in the archive", context);
  ObjSoup soup = read_obj(zip, entry.model_path);
  AssetModel model;
  model.id = entry.id;
  model.size_m = entry.size_m;
  model.warnings = std::move(soup.warnings);
  if (soup.triangles.empty()) fail("{}: no triangles (only points or lines, or every face invalid)", context);
  const ModelTransform transform = normalising_transform(soup, entry.model_rotation, entry.size_m, context, model.warnings);
  apply_transform(transform, soup);
  model.meshes = build_meshes(soup, model.warnings);
  if (model.meshes.empty()) fail("{}: every triangle has zero area", context);
  add_used_materials(soup, zip, model);
  return model;
}

}  // namespace

AssetModel load_model(const AssetEntry& entry) {
  const std::string context = entry.archive.string() + ": " + entry.model_path + " (entry '" + entry.id + "')";
  return load_checked(entry, context);
}

size_t AssetModel::triangle_count() const {
  size_t count = 0;
  for (const AssetMesh& mesh : meshes) count += mesh.indices.size() / 3;
  return count;
}

size_t AssetModel::vertex_count() const {
  size_t count = 0;
  for (const AssetMesh& mesh : meshes) count += mesh.positions.size();
  return count;
}

glm::vec3 AssetModel::bounds_min() const {
  glm::vec3 lo(std::numeric_limits<float>::max());
  for (const AssetMesh& mesh : meshes) {
    for (const glm::vec3& p : mesh.positions) lo = glm::min(lo, p);
  }
  return vertex_count() == 0 ? glm::vec3(0.0f) : lo;
}

glm::vec3 AssetModel::bounds_max() const {
  glm::vec3 hi(std::numeric_limits<float>::lowest());
  for (const AssetMesh& mesh : meshes) {
    for (const glm::vec3& p : mesh.positions) hi = glm::max(hi, p);
  }
  return vertex_count() == 0 ? glm::vec3(0.0f) : hi;
}

}  // namespace phyir::scenes
