#pragma once
// One piece of furniture of a Sweet Home 3D furniture library (.sh3f), as its catalog
// (PluginFurnitureCatalog.properties) describes it. Catalog lengths are centimetres; here
// every length is in metres and every position is in the normalised model frame of
// docs/assets.md: +X right, +Y up, +Z towards the front (the side facing the viewer in Sweet
// Home 3D's plan, glTF's front), the size box spanning x, z in [-size/2, size/2], y in
// [0, size.y].
#include <glm/glm.hpp>

#include <filesystem>
#include <string>
#include <vector>

namespace phyir::scenes {

// A lamp's light source. Sweet Home 3D places it by a fraction of the piece's size, so it
// follows the piece when resized.
struct AssetLightSource {
  // Fractions of the size box along our axes: x from the left (-X) side, y from the bottom,
  // z from the back (-Z) side. (The catalog's lightSourceY counts from the front: z = 1 - y/depth.)
  glm::vec3 relative_position{0.5f};
  // 0xRRGGBB / 255 taken as linear: Sweet Home 3D multiplies these bytes into the light's
  // power unchanged, so they scale intensity (often dim, e.g. #070605 for 5 small bulbs).
  glm::vec3 colour{1.0f};
  float diameter_m = 0.065f;  // Sweet Home 3D's default radius is 3.25 cm when none is given

  // Position in metres in the normalised model frame of a piece of this size.
  glm::vec3 position(glm::vec3 size_m) const {
    return (relative_position - glm::vec3(0.5f, 0.0f, 0.5f)) * size_m;
  }
};

// A door or window leaf turning around a vertical hinge (doorOrWindowSash*).
struct AssetSash {
  float axis_x_m = 0.0f;  // hinge position from the left (-X) side
  float axis_z_m = 0.0f;  // hinge position from the back (-Z) side
  float width_m = 0.0f;   // leaf width (its radius of turn)
  // Radians, counter-clockwise seen from above, 0 along +X: the leaf points along
  // (cos a, 0, -sin a). Catalog degrees follow Java2D's arc on the plan, the same sense.
  float start_angle = 0.0f;
  float end_angle = 0.0f;
};

enum class OpeningKind { Door, Window };

// What a door or window needs to sit in a wall (doorOrWindow#N=true).
struct AssetOpening {
  OpeningKind kind = OpeningKind::Window;  // from the name, else the elevation: docs/assets.md
  float wall_thickness_m = 0.0f;  // the wall it is made for (default: the piece's depth)
  float wall_distance_m = 0.0f;   // from the back (-Z) side of the box to that wall's back side
  // SVG path data in the unit square of the front view (x right, y down from the top), the
  // hole it cuts; empty means the whole width x height rectangle.
  std::string cut_out_shape;
  bool wall_cut_out_on_both_sides = true;
  std::vector<AssetSash> sashes;
};

struct AssetEntry {
  // Where it comes from.
  std::string library;             // the catalog's name, e.g. "Blend Swap CC-0"
  std::filesystem::path archive;   // the .sh3f file
  int index = 0;                   // N of the catalog's key#N
  std::string licence;             // the catalog's license= line, the same for every entry
  std::string creator;             // author of this model (attribution for CC-BY)
  // The model's own licence note inside the archive (a .txt beside the OBJ, as Blend Swap
  // models have: author, source, licence), or empty.
  std::string licence_file;

  std::string id;                  // e.g. "Kator Legaz#window-01"; unique in a library
  std::string name;
  std::string category;            // "Living room", "Kitchen", "Doors and windows", ...
  std::vector<std::string> tags;
  std::string description;
  std::string creation_date;       // yyyy-mm-dd as written

  std::string model_path;          // OBJ inside the archive, without the leading '/'
  std::string icon_path;
  bool multi_part_model = false;   // the model's folder holds its MTL and textures

  glm::vec3 size_m{0.0f};          // width (x), height (y), depth (z)
  float elevation_m = 0.0f;        // height of the bottom above the floor
  // Where objects dropped on it rest, as a fraction of its height (1 when absent); negative
  // means nothing should be put on it.
  float drop_on_top_elevation = 1.0f;
  // Applied to the OBJ's coordinates before normalisation: v' = model_rotation * v, rows as
  // the catalog lists the nine numbers. Identity when absent.
  glm::mat3 model_rotation{1.0f};
  bool movable = true;
  bool resizable = true;
  bool is_door_or_window = false;
  AssetOpening opening;            // meaningful when is_door_or_window
  std::vector<AssetLightSource> light_sources;  // non-empty for lamps
  std::string staircase_cut_out_shape;          // SVG path in the unit plan square, or empty

  bool is_light() const { return !light_sources.empty(); }
};

}  // namespace phyir::scenes
