#pragma once
// Sweet Home 3D's normalisation of a furniture model (ModelManager.getNormalizedTransform
// then the piece's size): rotate by modelRotation, then scale each axis so the rotated
// bounding box becomes the catalog's width x height x depth; here also moved so that the box
// is centred in x and z with its bottom at y = 0.
#include <glm/glm.hpp>

#include <string>
#include <vector>

#include "assets/asset_obj.h"

namespace phyir::scenes {

struct ModelTransform {
  glm::mat3 linear{1.0f};  // diag(scale) * rotation
  glm::vec3 offset{0.0f};  // p' = linear * p + offset
  bool flips_winding() const { return glm::determinant(linear) < 0.0f; }
  glm::vec3 point(glm::vec3 p) const { return linear * p + offset; }
};

// From the positions the triangles use. An axis along which the model is flat (extent below
// 1e-6 of the largest) cannot be stretched: it keeps scale 1 and a warning is added.
// Throws phyir::Error starting with `context` when the model has no extent at all.
ModelTransform normalising_transform(const ObjSoup& soup, const glm::mat3& rotation, glm::vec3 size_m,
                                     const std::string& context, std::vector<std::string>& warnings);

// Positions through the transform; normals through its inverse transpose, renormalised;
// triangle winding reversed when the transform mirrors, so fronts stay counter-clockwise.
void apply_transform(const ModelTransform& transform, ObjSoup& soup);

}  // namespace phyir::scenes
