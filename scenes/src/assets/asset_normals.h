#pragma once
// Shading normals of an OBJ model's triangles: the file's own where a triangle has them,
// otherwise generated as Sweet Home 3D's loader does (Java 3D's NormalGenerator): flat for
// faces outside smoothing groups ("s off", or no "s" at all), and for faces in a group the
// area-weighted mean of the group's faces around the vertex whose normals lie within 90
// degrees (its crease angle) of this face's.
#include <glm/glm.hpp>

#include <vector>

#include "assets/asset_obj.h"

namespace phyir::scenes {

// Three unit normals per triangle (corner order). The soup must be in its final frame
// (after apply_transform), so the crease test sees the shape as it will be drawn.
std::vector<glm::vec3> corner_normals(const ObjSoup& soup);

// Twice the triangle's area times its unit normal (counter-clockwise front).
glm::vec3 area_normal(const ObjSoup& soup, const ObjTriangle& triangle);

}  // namespace phyir::scenes
