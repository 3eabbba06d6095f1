#pragma once
// A furniture model loaded from its .sh3f archive and normalised the way Sweet Home 3D
// places it: modelRotation applied, then scaled (non-uniformly) so that its bounding box is
// exactly the catalog's width x height x depth, centred in x and z, bottom at y = 0, front
// towards +Z. Metres, +Y up, right-handed: glTF's conventions (docs/conventions.md).
#include <glm/glm.hpp>

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "phyir/scenes/asset_entry.h"
#include "phyir/scenes/asset_material.h"

namespace phyir::scenes {

// An image file from the archive, undecoded.
struct AssetTexture {
  std::string name;                  // path inside the archive
  std::vector<unsigned char> bytes;  // the JPEG or PNG file
  bool has_alpha = false;            // a PNG with an alpha channel or a tRNS chunk
};

// Triangles of one material. Attribute arrays have one entry per position.
struct AssetMesh {
  int material = 0;                  // index into AssetModel::materials
  std::vector<glm::vec3> positions;  // metres, normalised frame
  std::vector<glm::vec3> normals;    // unit; from the OBJ, else generated (docs/assets.md)
  std::vector<glm::vec2> texcoords;  // glTF convention (v = 1 - OBJ's v); empty if none
  std::vector<uint32_t> indices;     // counter-clockwise triangles
};

struct AssetModel {
  std::string id;                    // the entry's id
  glm::vec3 size_m{0.0f};            // the catalog size the model was scaled to
  std::vector<AssetMesh> meshes;
  std::vector<AssetMaterial> materials;
  std::vector<AssetTexture> textures;
  // What was approximated: unresolved texture files, degenerate faces, a flat model...
  std::vector<std::string> warnings;

  size_t triangle_count() const;
  size_t vertex_count() const;
  // Bounds of every mesh position; (0, 0) for an empty model.
  glm::vec3 bounds_min() const;
  glm::vec3 bounds_max() const;
};

// Reads the entry's OBJ, its MTL and textures from its archive and normalises it. Throws
// phyir::Error naming the archive, the model and the problem (missing file, no triangles,
// unreadable OBJ); everything approximated is in AssetModel::warnings.
AssetModel load_model(const AssetEntry& entry);

}  // namespace phyir::scenes
