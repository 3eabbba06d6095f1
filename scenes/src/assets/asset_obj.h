#pragma once
// An OBJ model read from a furniture archive by tinyobjloader, its MTL read from the same
// archive, as triangles indexing the OBJ's own arrays (nothing transformed yet).
#include <glm/glm.hpp>

#include <string>
#include <vector>

#include "phyir/scenes/asset_material.h"

namespace phyir::scenes {

class ZipArchive;

struct ObjCorner {
  int position = -1;
  int texcoord = -1;  // -1: none
  int normal = -1;    // -1: none
};

struct ObjTriangle {
  ObjCorner corners[3];
  int material = 0;        // index into ObjSoup::materials
  unsigned smoothing = 0;  // OBJ smoothing group; 0 = flat ("s off" or no s statement)
};

struct ObjSoup {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec2> texcoords;  // as in the OBJ (v up)
  std::vector<glm::vec3> normals;
  std::vector<ObjTriangle> triangles;
  std::vector<MtlMaterial> materials;  // the MTL's, then one default for faces without one
  std::string mtl_folder;              // archive folder the MTL was read from (textures resolve there)
  std::vector<std::string> warnings;
};

// Throws phyir::Error naming the archive and `obj_path` when the OBJ is missing or
// tinyobjloader refuses it. A missing MTL or an unknown material is a warning (the default
// material, white as in Sweet Home 3D); out-of-range indices drop their face with a warning.
ObjSoup read_obj(const ZipArchive& zip, const std::string& obj_path);

// "a/b/../c.obj" -> folder "a/" joined with a relative name, '\\' read as '/', "./" removed.
std::string archive_join(const std::string& folder, const std::string& relative);
std::string archive_folder(const std::string& path);

}  // namespace phyir::scenes
