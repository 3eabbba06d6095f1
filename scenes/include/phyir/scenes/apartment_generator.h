#pragma once
// The scene generator's "apartment" preset: an apartment plan (apartment_plan.h), its
// shell (apartment_shell.h) and furniture from a Sweet Home 3D library
// (apartment_furnishing.h), lit by a sky and the sun by day or by its lamps at night,
// written as one self-contained glTF (docs/apartments.md). The same (seed, index, options)
// and library give byte-identical files.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <vector>

#include <nlohmann/json.hpp>

#include "phyir/scenes/apartment_furnishing.h"
#include "phyir/scenes/room_generator.h"

namespace phyir::scenes {

struct ApartmentViewpoint {
  int room = -1;
  glm::vec3 position{0.0f};  // on a millimetre grid
  float clearance = 0.0f;    // metres to the nearest wall or piece's box
};

// Up to 8 viewpoints per room (room_layout.h's rules), rooms in plan order.
std::vector<ApartmentViewpoint> plan_apartment_viewpoints(const ApartmentPlan& plan,
                                                          const std::vector<PlacedAsset>& items);

struct ApartmentOptions {
  std::optional<ApartmentLighting> lighting;  // unset: day or night from the seed
  int rooms = 0;                              // 0: 2 to 6 from the seed
  // Declare the windows to the outside as light portals (extras.phyir.portals), through which
  // renderers sample the sky. Off by default: on the suite's day apartments, whose sun
  // dominates, they cost more time than they save (docs/gltf-support.md#light-portals).
  bool portals = false;
};

struct ApartmentSummary {
  RoomSummary files;           // what the .gltf holds (RoomSummary's fields)
  int rooms = 0;
  ApartmentLighting lighting = ApartmentLighting::Day;
  size_t pieces = 0;           // placed library pieces, doors and windows included
  size_t lamps_lit = 0;
  size_t punctual_lights = 0;  // the lamps' light sources and the sun
  nlohmann::json attributions; // [{name, library, creator, licence, id}] of every piece used, once each
  std::vector<std::string> missing_roles;  // roles the library had no model for, sorted, once each
};

// Writes apartment_<index>.gltf, its .bin, images and (by day) its sky into out_dir.
ApartmentSummary generate_apartment(const std::filesystem::path& out_dir, int index, uint64_t seed,
                                    const AssetLibrary& library, const ApartmentOptions& options);

}  // namespace phyir::scenes
