// phyir assets info ID [--assets DIR]: one catalog entry and its normalised model.
#include <fmt/format.h>

#include <chrono>
#include <iostream>
#include <memory>
#include <string>

#include "command_assets.h"

namespace phyir::cli {

namespace {

struct InfoOptions {
  std::string dir = scenes::kDefaultAssetDir.string();
  std::string id;
};

std::string vec(glm::vec3 v) { return fmt::format("({:.3f}, {:.3f}, {:.3f})", v.x, v.y, v.z); }

const char* alpha_mode(scenes::AssetAlphaMode mode) {
  return mode == scenes::AssetAlphaMode::Opaque ? "opaque" : mode == scenes::AssetAlphaMode::Mask ? "mask" : "blend";
}

void print_entry(const scenes::AssetEntry& e) {
  std::cout << fmt::format("{}\n  name: {}\n  category: {}\n  library: {} ({})\n  licence: {}\n  creator: {}\n", e.id,
                           e.name, e.category, e.library, e.archive.string(), e.licence, e.creator);
  std::string tags;
  for (const std::string& t : e.tags) tags += (tags.empty() ? "" : ", ") + t;
  if (!e.licence_file.empty()) std::cout << fmt::format("  licence note: {} (in the archive)\n", e.licence_file);
  std::cout << fmt::format("  tags: {}\n  model: {}\n  size (m): {} (width x height x depth)\n", tags, e.model_path,
                           vec(e.size_m));
  std::cout << fmt::format("  elevation: {:.3f} m, drop on top at {:.3f} of the height, movable: {}\n", e.elevation_m,
                           e.drop_on_top_elevation, e.movable);
  for (const scenes::AssetLightSource& s : e.light_sources) {
    std::cout << fmt::format("  light source at {} m, colour {}, diameter {:.3f} m\n", vec(s.position(e.size_m)),
                             vec(s.colour), s.diameter_m);
  }
  if (e.is_door_or_window) {
    const scenes::AssetOpening& o = e.opening;
    std::cout << fmt::format("  {}: wall thickness {:.3f} m, wall distance {:.3f} m, cut-out '{}', {} sash(es)\n",
                             o.kind == scenes::OpeningKind::Door ? "door" : "window", o.wall_thickness_m,
                             o.wall_distance_m, o.cut_out_shape, o.sashes.size());
  }
}

void print_model(const scenes::AssetModel& m, double seconds) {
  std::cout << fmt::format("model: {} meshes, {} triangles, {} vertices, loaded in {:.3f} s\n", m.meshes.size(),
                           m.triangle_count(), m.vertex_count(), seconds);
  std::cout << fmt::format("  bounds: {} .. {}\n", vec(m.bounds_min()), vec(m.bounds_max()));
  for (size_t i = 0; i < m.materials.size(); ++i) {
    const scenes::AssetMaterial& a = m.materials[i];
    std::string texture = a.base_color_texture >= 0 ? m.textures[static_cast<size_t>(a.base_color_texture)].name : "-";
    std::cout << fmt::format("  material {} '{}': base {} roughness {:.3f} metallic {:.2f} transmission {:.2f} "
                             "ior {:.2f} alpha {:.2f} ({}), texture {}, {} triangles\n",
                             i, a.name, vec(a.base_color), a.roughness, a.metallic, a.transmission, a.ior, a.alpha,
                             alpha_mode(a.alpha_mode), texture, m.meshes[i].indices.size() / 3);
  }
  for (const scenes::AssetTexture& t : m.textures) {
    std::cout << fmt::format("  texture {}: {} bytes{}\n", t.name, t.bytes.size(), t.has_alpha ? ", alpha" : "");
  }
  for (const std::string& w : m.warnings) std::cout << "  warning: " << w << "\n";
}

void run(const InfoOptions& options) {
  const scenes::AssetLibrary library = open_asset_library(options.dir);
  const scenes::AssetEntry& entry = library.at(options.id);
  print_entry(entry);
  const auto start = std::chrono::steady_clock::now();
  const scenes::AssetModel model = scenes::load_model(entry);
  print_model(model, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
}

}  // namespace

void add_assets_info_command(CLI::App& assets) {
  auto options = std::make_shared<InfoOptions>();
  auto* cmd = assets.add_subcommand(
      "info", "One entry in full (catalog keys, licence, light sources, door or window data), then its "
              "model loaded and normalised: meshes, triangles, bounds, PBR materials, textures, warnings");
  cmd->add_option("id", options->id, "Entry id as `phyir assets list` prints it, e.g. \"Kator Legaz#window-01\"")
      ->required();
  add_assets_dir_option(*cmd, options->dir);
  cmd->callback([options] { run(*options); });
}

}  // namespace phyir::cli
