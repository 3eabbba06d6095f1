// The placed pieces as glTF: their meshes in world space, their materials (a share turned
// into the paper's specular kinds), their textures copied from the archives, and the lit
// lamps' point lights (docs/apartments.md, "Materials" and "Lamps").
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "generator/apartment/apartment_gltf.h"
#include "phyir/scenes/lamp_light.h"

namespace phyir::scenes {

namespace {

constexpr float kReassignedShare = 0.2f;  // of the furniture's untextured opaque materials
constexpr float kLumensPerWatt = 683.0f;
constexpr float kShadeShare = 0.5f;  // of a lit lamp's flux, when it has a shade

float lamp_lumens(const std::string& role) {
  if (role == "ceiling_light") return 1000.0f;
  if (role == "floor_lamp") return 800.0f;
  return 400.0f;  // table lamps
}

// The catalog's light colour normalised to its brightest channel (white when black).
glm::vec3 light_tint(const glm::vec3& c) {
  const float peak = std::max({c.x, c.y, c.z});
  return peak > 0.0f ? c / peak : glm::vec3(1.0f);
}

bool is_fitting(const std::string& role) { return role.find("door") != std::string::npos || role.find("window") != std::string::npos; }
bool is_lamp(const PlacedAsset& p) { return p.entry->is_light(); }

std::string sanitized(const std::string& s) {
  std::string out;
  for (char c : s) out += (std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '_' || c == '-') ? c : '_';
  return out;
}

// ".png" or ".jpg" from the file's first bytes (archives hold both, not always named so).
std::string image_extension(const std::vector<unsigned char>& bytes) {
  return bytes.size() >= 4 && bytes[0] == 0x89 && bytes[1] == 'P' ? ".png" : ".jpg";
}

class PieceWriter {
 public:
  PieceWriter(GltfDocument& doc, AssetModelCache& models, const std::string& stem, Pcg32& rng)
      : doc_(doc), models_(models), stem_(stem), rng_(rng) {}

  void add(const PlacedAsset& piece, size_t index, PiecesWritten& out) {
    const AssetModel& model = models_.get(*piece.entry);
    const glm::mat4 to_world = piece.model_to_world();
    const glm::mat3 normal_matrix = glm::transpose(glm::inverse(glm::mat3(to_world)));
    const float glow = shade_radiance(piece, model, to_world);
    for (size_t k = 0; k < model.meshes.size(); ++k) {
      const AssetMesh& mesh = model.meshes[k];
      const Part part = part_of(piece, model, mesh);
      if (part == Part::LeftOut) continue;
      GltfMesh g;
      g.name = fmt::format("{}_{}_{}", piece.role, index, k);
      g.material = material(piece, model, mesh.material, part == Part::Shade ? glow : 0.0f);
      for (const glm::vec3& p : mesh.positions) g.positions.push_back(glm::vec3(to_world * glm::vec4(p, 1.0f)));
      for (const glm::vec3& n : mesh.normals) g.normals.push_back(glm::normalize(normal_matrix * n));
      // A textured material on a mesh without texture coordinates reads the texture's middle.
      if (doc_.materials[size_t(g.material)].base_color_texture.present())
        g.texcoords0 = mesh.texcoords.empty() ? std::vector<glm::vec2>(mesh.positions.size(), glm::vec2(0.5f))
                                              : mesh.texcoords;
      g.indices = mesh.indices;
      g.extras = {{"asset", {{"name", piece.entry->name}, {"id", piece.entry->id}, {"library", piece.entry->library},
                             {"creator", piece.entry->creator}, {"licence", piece.entry->licence}, {"role", piece.role},
                             {"room", piece.room}}}};
      doc_.meshes.push_back(std::move(g));
    }
    if (attributed_.insert(piece.entry->library + "|" + piece.entry->id).second)
      out.attributions.push_back({{"name", piece.entry->name}, {"id", piece.entry->id}, {"library", piece.entry->library},
                                  {"creator", piece.entry->creator}, {"licence", piece.entry->licence}});
    if (piece.lamp_on) {
      add_lights(piece, model, index, glow > 0.0f);
      ++out.lamps_lit;
    }
  }

  std::vector<std::string> kinds() const { return {kinds_.begin(), kinds_.end()}; }

 private:
  enum class Part { Kept, LeftOut, Shade };

  // Window and door panes are left out (a dielectric pane would block next-event estimation
  // of the sun; docs/apartments.md). A lamp's meshes around a light source are its bulb and
  // glass, left out (the point light stands for them) when see-through or no bigger than
  // 2.5 source diameters, and otherwise its shade, which glows when the lamp is on.
  static Part part_of(const PlacedAsset& piece, const AssetModel& model, const AssetMesh& mesh) {
    const AssetMaterial& m = model.materials[size_t(mesh.material)];
    const bool see_through = m.transmission > 0.0f || m.alpha_mode == AssetAlphaMode::Blend;
    if (is_fitting(piece.role)) return see_through ? Part::LeftOut : Part::Kept;
    if (!is_lamp(piece)) return Part::Kept;
    glm::vec3 lo(1e30f), hi(-1e30f);
    for (const glm::vec3& p : mesh.positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
    for (const AssetLightSource& s : piece.entry->light_sources) {
      const glm::vec3 at = s.position(piece.entry->size_m);
      const bool encloses = glm::all(glm::greaterThanEqual(at, lo - 0.01f)) && glm::all(glm::lessThanEqual(at, hi + 0.01f));
      if (!encloses) continue;
      const float extent = std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z});
      return see_through || extent <= 2.5f * std::max(s.diameter_m, 0.05f) ? Part::LeftOut : Part::Shade;
    }
    return Part::Kept;
  }

  static double world_area(const AssetMesh& mesh, const glm::mat4& to_world) {
    double area = 0.0;
    for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
      const glm::vec3 a(to_world * glm::vec4(mesh.positions[mesh.indices[t]], 1.0f));
      const glm::vec3 b(to_world * glm::vec4(mesh.positions[mesh.indices[t + 1]], 1.0f));
      const glm::vec3 c(to_world * glm::vec4(mesh.positions[mesh.indices[t + 2]], 1.0f));
      area += 0.5 * double(glm::length(glm::cross(b - a, c - a)));
    }
    return area;
  }

  // The radiance of a lit lamp's shades: kShadeShare of its flux leaves through them, from
  // both faces (the library's materials are double-sided), as a Lambertian emitter:
  // L = share x flux / (2 pi area).
  float shade_radiance(const PlacedAsset& piece, const AssetModel& model, const glm::mat4& to_world) const {
    if (!piece.lamp_on) return 0.0f;
    double area = 0.0;
    for (const AssetMesh& mesh : model.meshes)
      if (part_of(piece, model, mesh) == Part::Shade) area += world_area(mesh, to_world);
    if (!(area > 1e-6)) return 0.0f;
    const double watts = kShadeShare * lamp_lumens(piece.role) / kLumensPerWatt;
    return float(watts / (2.0 * 3.14159265358979 * area));
  }

  int texture(const AssetEntry& entry, const AssetModel& model, int t) {
    const AssetTexture& tex = model.textures[size_t(t)];
    const std::string key = entry.archive.string() + "|" + tex.name;
    auto it = textures_.find(key);
    if (it != textures_.end()) return it->second;
    GltfTexture g;
    g.uri = fmt::format("{}_textures/{}_{}{}", stem_, sanitized(entry.archive.stem().string()),
                        sanitized((std::filesystem::path(tex.name).parent_path() / std::filesystem::path(tex.name).stem()).string()),
                        image_extension(tex.bytes));
    g.source.bytes.assign(tex.bytes.begin(), tex.bytes.end());
    doc_.textures.push_back(std::move(g));
    return textures_[key] = static_cast<int>(doc_.textures.size()) - 1;
  }

  int material(const PlacedAsset& piece, const AssetModel& model, int m, float glow) {
    const std::string key = piece.entry->archive.string() + "|" + piece.entry->id + "|" + std::to_string(m) +
                            (glow > 0.0f ? fmt::format("|glow {}", glow) : "");
    auto it = materials_.find(key);
    if (it != materials_.end()) return it->second;
    const AssetMaterial& a = model.materials[size_t(m)];
    GltfMaterial g;
    g.name = sanitized(piece.entry->name + "_" + a.name);
    g.base_color_factor = glm::vec4(a.base_color, a.alpha_mode == AssetAlphaMode::Opaque ? 1.0f : a.alpha);
    if (a.base_color_texture >= 0) g.base_color_texture.texture = texture(*piece.entry, model, a.base_color_texture);
    g.metallic_factor = a.metallic;
    g.roughness_factor = a.roughness;
    g.transmission_factor = a.transmission;
    if (a.transmission > 0.0f) g.ior = a.ior;
    g.alpha_mode = a.alpha_mode == AssetAlphaMode::Mask ? AlphaMode::Mask
                   : a.alpha_mode == AssetAlphaMode::Blend ? AlphaMode::Blend : AlphaMode::Opaque;
    g.double_sided = a.double_sided;
    if (glow > 0.0f) set_glow(g, piece, glow);
    const bool plain_opaque = a.transmission == 0.0f && a.alpha_mode == AssetAlphaMode::Opaque;
    if (plain_opaque && !is_fitting(piece.role) && !is_lamp(piece) && rng_.chance(kReassignedShare))
      reassign(g, a.base_color_texture >= 0);
    doc_.materials.push_back(std::move(g));
    return materials_[key] = static_cast<int>(doc_.materials.size()) - 1;
  }

  // The paper's specular cases on real furniture: glossy lacquer, rough and polished metal,
  // mirror and glass. Textured materials only become lacquer (their texture stays).
  void reassign(GltfMaterial& g, bool textured) {
    static const glm::vec3 kMetals[] = {{0.56f, 0.57f, 0.58f}, {0.91f, 0.92f, 0.92f}, {0.95f, 0.64f, 0.54f}, {1.0f, 0.71f, 0.29f}};
    const float u = textured ? 0.0f : rng_.uniform();
    const glm::vec3 metal = kMetals[rng_.below(4)];
    const char* kind = "glossy";
    if (u < 0.3f) {
      g.roughness_factor = rng_.uniform(0.05f, 0.25f), g.metallic_factor = 0.0f;
    } else if (u < 0.5f) {
      g.base_color_factor = glm::vec4(metal, 1.0f), g.metallic_factor = 1.0f, g.roughness_factor = rng_.uniform(0.35f, 0.6f);
      kind = "metal_rough";
    } else if (u < 0.7f) {
      g.base_color_factor = glm::vec4(metal, 1.0f), g.metallic_factor = 1.0f, g.roughness_factor = rng_.uniform(0.05f, 0.15f);
      kind = "metal_polished";
    } else if (u < 0.85f) {
      g.base_color_factor = glm::vec4(0.95f, 0.95f, 0.95f, 1.0f), g.metallic_factor = 1.0f, g.roughness_factor = 0.0f;
      kind = "mirror";
    } else {
      g.base_color_factor = glm::vec4(1.0f), g.metallic_factor = 0.0f, g.roughness_factor = 0.0f;
      g.transmission_factor = 1.0f, g.ior = 1.5f, g.double_sided = true;
      kind = "glass";
    }
    kinds_.insert(kind);
    g.name += std::string("_") + kind;
  }

  // A glowing shade: the lamp's first source's tint, `radiance` in W/(sr m^2).
  static void set_glow(GltfMaterial& g, const PlacedAsset& piece, float radiance) {
    g.emissive_factor = light_tint(piece.entry->light_sources.front().colour);
    g.emissive_strength = radiance;
    g.name += "_glowing";
  }

  // The point lights carry the flux the shades do not.
  void add_lights(const PlacedAsset& piece, const AssetModel& model, size_t index, bool shaded) {
    const auto& sources = piece.entry->light_sources;
    const float share = shaded ? 1.0f - kShadeShare : 1.0f;
    const float watts = share * lamp_lumens(piece.role) / kLumensPerWatt / float(sources.size());
    std::vector<const AssetMesh*> surfaces;  // what the lamp keeps: its light must clear them
    for (const AssetMesh& mesh : model.meshes)
      if (part_of(piece, model, mesh) != Part::LeftOut) surfaces.push_back(&mesh);
    for (size_t s = 0; s < sources.size(); ++s) {
      GltfLight light;
      light.name = fmt::format("{}_{}_light_{}", piece.role, index, s);
      light.type = PunctualLight::Type::Point;
      const glm::vec3 at = clear_of_surfaces(surfaces, sources[s].position(piece.entry->size_m), 0.5f * sources[s].diameter_m);
      light.position = glm::vec3(piece.model_to_world() * glm::vec4(at, 1.0f));
      light.set_radiometric(light_tint(sources[s].colour) * (watts / (4.0f * 3.14159265f)));  // isotropic: W / 4 pi sr
      doc_.lights.push_back(std::move(light));
    }
  }

  GltfDocument& doc_;
  AssetModelCache& models_;
  std::string stem_;
  Pcg32& rng_;
  std::map<std::string, int> textures_, materials_;
  std::set<std::string> attributed_, kinds_;
};

}  // namespace

PiecesWritten add_apartment_pieces(GltfDocument& doc, const ApartmentFurnishing& furnishing, AssetModelCache& models,
                                   const std::string& stem, Pcg32& rng) {
  PiecesWritten out;
  PieceWriter writer(doc, models, stem, rng);
  for (size_t i = 0; i < furnishing.items.size(); ++i) writer.add(furnishing.items[i], i, out);
  out.material_kinds = writer.kinds();
  return out;
}

}  // namespace phyir::scenes
