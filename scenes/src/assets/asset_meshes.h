#pragma once
// Indexed triangle meshes, one per material, from an OBJ soup in its final frame.
#include <string>
#include <vector>

#include "assets/asset_obj.h"
#include "phyir/scenes/asset_model.h"

namespace phyir::scenes {

// Corners sharing position, texture coordinate and normal become one vertex; texture
// coordinates flip to glTF's v (1 - v). Zero-area triangles are dropped with a warning;
// coincident twins in one material (scenes/triangle_corners.h) silently, the first kept.
// Meshes come in material order; materials no triangle uses get no mesh.
std::vector<AssetMesh> build_meshes(const ObjSoup& soup, std::vector<std::string>& warnings);

}  // namespace phyir::scenes
