#include "phyir/scenes/scene_info.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <cmath>
#include <map>

#include "phyir/core/safe_math.h"

namespace phyir::scenes {

namespace {

using nlohmann::json;

// Which texture slots a material fills, by their glTF names.
std::vector<std::string> texture_uses(const Material& m) {
  std::vector<std::string> uses;
  if (m.base_color_texture.present()) uses.emplace_back("baseColor");
  if (m.metallic_roughness_texture.present()) uses.emplace_back("metallicRoughness");
  if (m.normal_texture.present()) uses.emplace_back("normal");
  if (m.emissive_texture.present()) uses.emplace_back("emissive");
  if (m.transmission_texture.present()) uses.emplace_back("transmission");
  return uses;
}

glm::vec3 mean_texel(const Texture& texture) {
  if (!texture.has_texels()) return glm::vec3(1.0f);  // not decoded: the factor alone
  glm::dvec3 sum(0.0);
  for (int y = 0; y < texture.height(); ++y)
    for (int x = 0; x < texture.width(); ++x) sum += glm::dvec3(texture.texel(x, y));
  return glm::vec3(sum / static_cast<double>(texture.texel_count()));
}

const char* texel_format_name(TexelFormat format) {
  switch (format) {
    case TexelFormat::Srgb8: return "srgb8";
    case TexelFormat::Unorm8: return "unorm8";
    case TexelFormat::Half: return "half";
    case TexelFormat::Float: return "float";
  }
  return "?";
}

// "textures: 300, 151.9 MiB with their mip levels (srgb8 202, unorm8 98)".
std::string texture_memory_text(const std::vector<Texture>& textures) {
  size_t bytes = 0;
  std::map<std::string, int> per_format;
  for (const Texture& t : textures) {
    bytes += t.bytes();
    if (t.has_texels()) ++per_format[texel_format_name(t.format())];
  }
  std::vector<std::string> formats;
  for (const auto& [name, count] : per_format) formats.push_back(fmt::format("{} {}", name, count));
  const std::string by_format = formats.empty() ? "not decoded" : fmt::format("{}", fmt::join(formats, ", "));
  return fmt::format("textures: {}, {:.1f} MiB with their mip levels ({})\n", textures.size(),
                     double(bytes) / (1 << 20), by_format);
}

struct EmitterSummary {
  size_t meshes = 0;
  size_t triangles = 0;
  double area = 0.0;      // m^2
  glm::dvec3 power{0.0};  // W per channel
};

// Each emissive triangle as a Lambertian emitter of radiance L: flux = pi * L * area, per
// emitting side. L is the material's emission times the emissive texture's mean texel, so
// the figure is an estimate when the texture varies across the surface.
EmitterSummary summarize_emitters(const Scene& scene) {
  EmitterSummary summary;
  for (const Mesh& mesh : scene.meshes) {
    if (mesh.material < 0 || static_cast<size_t>(mesh.material) >= scene.materials.size()) continue;
    const Material& m = scene.materials[static_cast<size_t>(mesh.material)];
    if (!m.is_emissive()) continue;
    glm::vec3 radiance = m.emission();
    const int t = m.emissive_texture.texture;
    if (t >= 0 && static_cast<size_t>(t) < scene.textures.size())
      radiance *= mean_texel(scene.textures[static_cast<size_t>(t)]);
    double area = 0.0;
    for (const glm::uvec3& tri : mesh.triangles) {
      const glm::dvec3 a(mesh.positions[tri.x]), b(mesh.positions[tri.y]), c(mesh.positions[tri.z]);
      area += 0.5 * glm::length(glm::cross(b - a, c - a));
    }
    ++summary.meshes;
    summary.triangles += mesh.triangles.size();
    summary.area += area;
    summary.power += glm::dvec3(radiance) * (kPi * area * (m.double_sided ? 2.0 : 1.0));
  }
  return summary;
}

std::map<int, size_t> meshes_per_material(const Scene& scene) {
  std::map<int, size_t> counts;
  for (const Mesh& mesh : scene.meshes) ++counts[mesh.material];
  return counts;
}

size_t vertex_count(const Scene& scene) {
  size_t n = 0;
  for (const Mesh& mesh : scene.meshes) n += mesh.positions.size();
  return n;
}

template <typename Vec>
json to_json(const Vec& v) {
  json array = json::array();
  for (int i = 0; i < static_cast<int>(Vec::length()); ++i) array.push_back(v[i]);
  return array;
}

json source_json(const SourceInfo& info) {
  return {{"nodes", info.nodes},
          {"meshes", info.meshes},
          {"primitives", info.primitives},
          {"mesh_instances", info.mesh_instances},
          {"gpu_instances", info.gpu_instances},
          {"unique_triangles", info.unique_triangles},
          {"materials", info.materials},
          {"textures", info.textures},
          {"images", info.images},
          {"samplers", info.samplers},
          {"cameras", info.cameras},
          {"lights", info.lights},
          {"default_scene", info.default_scene},
          {"extensions_used", info.extensions_used},
          {"extensions_required", info.extensions_required},
          {"generator", info.generator}};
}

json materials_json(const Scene& scene) {
  const std::map<int, size_t> uses = meshes_per_material(scene);
  json materials = json::array();
  for (size_t i = 0; i < scene.materials.size(); ++i) {
    const Material& m = scene.materials[i];
    const auto count = uses.find(static_cast<int>(i));
    materials.push_back({{"index", i},
                         {"name", m.name},
                         {"textures", texture_uses(m)},
                         {"extensions", m.extensions},
                         {"emissive", m.is_emissive()},
                         {"transmissive", m.is_transmissive()},
                         {"meshes", count != uses.end() ? count->second : 0}});
  }
  return materials;
}

json cameras_json(const Scene& scene) {
  json cameras = json::array();
  for (const Camera& c : scene.cameras) {
    cameras.push_back({{"name", c.name},
                       {"perspective", c.perspective},
                       {"position", to_json(c.position)},
                       {"forward", to_json(c.forward)},
                       {"up", to_json(c.up)},
                       {"yfov_degrees", c.yfov * 180.0f / kPi},
                       {"aspect_ratio", c.aspect_ratio}});
  }
  return cameras;
}

std::string format_vec3(const glm::vec3& v) { return fmt::format("({:.3g}, {:.3g}, {:.3g})", v.x, v.y, v.z); }

bool is_directional(const PunctualLight& light) { return light.type == PunctualLight::Type::Directional; }
const char* photometric_unit(const PunctualLight& light) { return is_directional(light) ? "lx" : "cd"; }
const char* radiometric_unit(const PunctualLight& light) { return is_directional(light) ? "W/m^2" : "W/sr"; }

json lights_json(const Scene& scene) {
  json lights = json::array();
  for (const PunctualLight& l : scene.lights) {
    json light = {{"name", l.name},
                  {"type", to_string(l.type)},
                  {"color", to_json(l.color)},
                  {"intensity", l.intensity},
                  {"intensity_unit", photometric_unit(l)},
                  {"radiometric", to_json(l.radiometric())},
                  {"radiometric_unit", radiometric_unit(l)},
                  {"range", l.range}};
    if (!is_directional(l)) light["position"] = to_json(l.position);
    if (l.type != PunctualLight::Type::Point) light["direction"] = to_json(l.direction);
    if (l.type == PunctualLight::Type::Spot) {
      light["inner_cone_degrees"] = l.inner_cone_angle * 180.0f / kPi;
      light["outer_cone_degrees"] = l.outer_cone_angle * 180.0f / kPi;
    }
    lights.push_back(light);
  }
  return lights;
}

std::string light_text(const PunctualLight& l) {
  std::string where = is_directional(l) ? fmt::format("towards {}", format_vec3(l.direction))
                                        : fmt::format("at {}", format_vec3(l.position));
  if (l.type == PunctualLight::Type::Spot)
    where += fmt::format(" towards {}, cone {:.1f} to {:.1f} deg", format_vec3(l.direction),
                         l.inner_cone_angle * 180.0f / kPi, l.outer_cone_angle * 180.0f / kPi);
  return fmt::format("  {}: {} {}, {:.4g} {} x colour {} = {:.4g} {} (luminance)\n", l.name, to_string(l.type),
                     where, l.intensity, photometric_unit(l), format_vec3(l.color), luminance(l.radiometric()),
                     radiometric_unit(l));
}

json environment_json(const Scene& scene) {
  if (!scene.environment) return nullptr;
  const SceneEnvironment& e = *scene.environment;
  return {{"uri", e.uri}, {"path", e.path.string()}, {"scale", e.scale}};
}

std::string environment_text(const Scene& scene) {
  if (!scene.environment) return "environment: none declared (a render's environment setting can add one)\n";
  const SceneEnvironment& e = *scene.environment;
  return fmt::format("environment: {} x {:.4g} (extras.phyir.environment; a render's environment setting overrides it)\n",
                     e.path.string(), e.scale);
}

}  // namespace

json scene_info_json(const Scene& scene) {
  const EmitterSummary emitters = summarize_emitters(scene);
  json textures = json::array();
  for (const Texture& t : scene.textures) {
    textures.push_back({{"name", t.name},
                        {"width", t.width()},
                        {"height", t.height()},
                        {"encoding", t.encoding == TextureEncoding::SrgbColour ? "srgb" : "linear"},
                        {"format", texel_format_name(t.format())},
                        {"levels", t.levels()},
                        {"bytes", t.bytes()}});
  }
  json viewpoints = json::array();
  for (const glm::vec3& p : scene.candidate_viewpoints) viewpoints.push_back(to_json(p));
  const Bounds bounds = scene.compute_bounds();
  return {{"source", scene.source},
          {"source_info", source_json(scene.info)},
          {"meshes", scene.meshes.size()},
          {"triangles", scene.triangle_count()},
          {"vertices", vertex_count(scene)},
          {"materials", materials_json(scene)},
          {"textures", textures},
          {"emitters",
           {{"meshes", emitters.meshes},
            {"triangles", emitters.triangles},
            {"area_m2", emitters.area},
            {"power_w", to_json(emitters.power)},
            {"power_luminance_w", luminance(glm::vec3(emitters.power))}}},
          {"lights", lights_json(scene)},
          {"cameras", cameras_json(scene)},
          {"candidate_viewpoints", viewpoints},
          {"environment", environment_json(scene)},
          {"bounds",
           bounds.empty() ? json(nullptr) : json{{"min", to_json(bounds.min)}, {"max", to_json(bounds.max)}}},
          {"warnings", scene.warnings}};
}

std::string scene_info_text(const Scene& scene) {
  const SourceInfo& s = scene.info;
  std::string out = fmt::format("scene: {}\n", scene.source);
  if (!s.generator.empty()) out += fmt::format("generator: {}\n", s.generator);
  out += fmt::format(
      "file: {} nodes, {} meshes ({} primitives), {} mesh instances in scene {}, {} materials, "
      "{} textures, {} images, {} samplers, {} cameras\n",
      s.nodes, s.meshes, s.primitives, s.mesh_instances, s.default_scene, s.materials, s.textures, s.images,
      s.samplers, s.cameras);
  if (!s.extensions_used.empty())
    out += fmt::format("extensions used: {}\n", fmt::join(s.extensions_used, ", "));
  if (!s.extensions_required.empty())
    out += fmt::format("extensions required: {}\n", fmt::join(s.extensions_required, ", "));
  out += fmt::format("geometry: {} meshes, {} triangles, {} vertices; {} unique triangles (each primitive once)\n",
                     scene.meshes.size(), scene.triangle_count(), vertex_count(scene), s.unique_triangles);
  if (!scene.textures.empty()) out += texture_memory_text(scene.textures);
  if (s.gpu_instances > 0)
    out += fmt::format("GPU instances: {} (EXT_mesh_gpu_instancing), baked into the meshes above\n",
                       s.gpu_instances);
  const Bounds bounds = scene.compute_bounds();
  if (!bounds.empty())
    out += fmt::format("bounds: {} to {}, size {}\n", format_vec3(bounds.min), format_vec3(bounds.max),
                       format_vec3(bounds.max - bounds.min));

  const std::map<int, size_t> uses = meshes_per_material(scene);
  out += fmt::format("materials ({}):\n", scene.materials.size());
  for (size_t i = 0; i < scene.materials.size(); ++i) {
    const Material& m = scene.materials[i];
    const auto count = uses.find(static_cast<int>(i));
    std::vector<std::string> notes{fmt::format("{} meshes", count != uses.end() ? count->second : 0)};
    if (const auto t = texture_uses(m); !t.empty())
      notes.push_back(fmt::format("textures {}", fmt::join(t, "+")));
    if (!m.extensions.empty()) notes.push_back(fmt::format("{}", fmt::join(m.extensions, ", ")));
    if (m.is_emissive()) notes.push_back(fmt::format("emissive {}", format_vec3(m.emission())));
    if (m.is_transmissive())
      notes.push_back(fmt::format("transmissive {:.2f}, ior {:.2f}", m.transmission_factor, m.ior));
    out += fmt::format("  [{}] {}: {}\n", i, m.name.empty() ? "(unnamed)" : m.name, fmt::join(notes, "; "));
  }

  const EmitterSummary e = summarize_emitters(scene);
  out +=
      fmt::format("emitters: {} meshes, {} triangles, {:.4g} m^2, power about {:.4g} W (RGB {})\n", e.meshes,
                  e.triangles, e.area, luminance(glm::vec3(e.power)), format_vec3(glm::vec3(e.power)));
  out += fmt::format("punctual lights ({}; radiometric = photometric / 683 lm/W):\n", scene.lights.size());
  for (const PunctualLight& l : scene.lights) out += light_text(l);
  out += fmt::format("cameras ({}):\n", scene.cameras.size());
  for (const Camera& c : scene.cameras) {
    out += fmt::format(
        "  {}: {} at {}, forward {}\n", c.name,
        c.perspective ? fmt::format("perspective yfov {:.1f} deg", c.yfov * 180.0f / kPi) : "orthographic",
        format_vec3(c.position), format_vec3(c.forward));
  }
  out += fmt::format("candidate viewpoints: {}\n", scene.candidate_viewpoints.size());
  out += environment_text(scene);
  out += fmt::format("warnings ({}):\n", scene.warnings.size());
  for (const std::string& w : scene.warnings) out += fmt::format("  - {}\n", w);
  return out;
}

}  // namespace phyir::scenes
