#pragma once
// Baking a primitive into world space, and the attributes glTF lets a client derive:
// flat normals when NORMAL is absent, tangents when a normal map needs them.
#include <glm/glm.hpp>

#include "gltf/read/gltf_primitives.h"
#include "phyir/scenes/scene.h"

namespace phyir::scenes::gltf {

// Positions by `world`; normals by its inverse transpose, renormalised; tangents by its
// upper 3x3. A mirroring transform (negative determinant) reverses the triangle winding
// and the tangent handedness so that the front face and the bitangent stay consistent.
// Without normals in the file the result gets flat normals and no tangents.
Mesh bake_to_world(const PrimitiveData& local, const glm::dmat4& world);

// Unshares vertices so that each triangle carries its own geometric normal (glTF 2.0
// 3.7.2.1: "client implementations MUST calculate flat normals").
void make_flat_normals(Mesh& mesh);

// Per-vertex tangents from the UV set `texcoord` (0 or 1): the per-triangle dP/du
// accumulated, orthogonalised against the normal. Handedness follows glTF: the
// bitangent cross(N, T) * w points towards decreasing v (up in the image).
// Returns false (mesh unchanged) when the mesh lacks that UV set.
bool generate_tangents(Mesh& mesh, int texcoord);

}  // namespace phyir::scenes::gltf
