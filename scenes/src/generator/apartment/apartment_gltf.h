#pragma once
// The apartment's glTF document, built in parts: the shell with its materials, the placed
// pieces with theirs and the lamps' lights (apartment_gltf_*.cpp).
#include <map>
#include <string>

#include "phyir/core/pcg32.h"
#include "phyir/scenes/apartment_furnishing.h"
#include "phyir/scenes/apartment_shell.h"
#include "phyir/scenes/gltf_writer.h"

namespace phyir::scenes {

// Walls, floors and ceilings of every room, from the room generator's palette (a palette
// per room, so rooms differ), and the outside's facade and roof. Procedural textures are
// written into `out_dir` as <stem>_<room>_<texture>.png.
void add_apartment_shell(GltfDocument& doc, const ApartmentPlan& plan, const std::filesystem::path& out_dir,
                         const std::string& stem);

// What add_apartment_pieces() reports.
struct PiecesWritten {
  size_t lamps_lit = 0;
  nlohmann::json attributions = nlohmann::json::array();  // one entry per library model used
  std::vector<std::string> material_kinds;                // reassigned kinds present
};

// Every placed piece's meshes (world space), its materials (some reassigned to the paper's
// specular kinds) and textures (copied from the archives under <stem>_textures/), and a
// point light per light source of every lit lamp.
PiecesWritten add_apartment_pieces(GltfDocument& doc, const ApartmentFurnishing& furnishing, AssetModelCache& models,
                                   const std::string& stem, Pcg32& rng);

}  // namespace phyir::scenes
