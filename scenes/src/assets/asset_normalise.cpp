// The normalising transform of a furniture model (docs/assets.md, "Normalisation").
#include "assets/asset_normalise.h"

#include <algorithm>
#include <limits>

#include "phyir/core/error.h"
#include "phyir/core/safe_math.h"

namespace phyir::scenes {

namespace {

// An extent below this fraction of the largest one is a flat model along that axis (a rug,
// a picture): float positions of a 1 m model are only good to about 1e-7 m.
constexpr float kFlatFraction = 1e-6f;

}  // namespace

ModelTransform normalising_transform(const ObjSoup& soup, const glm::mat3& rotation, glm::vec3 size_m,
                                     const std::string& context, std::vector<std::string>& warnings) {
  glm::vec3 lo(std::numeric_limits<float>::max());
  glm::vec3 hi(std::numeric_limits<float>::lowest());
  for (const ObjTriangle& t : soup.triangles) {
    for (const ObjCorner& c : t.corners) {
      const glm::vec3 p = rotation * soup.positions[static_cast<size_t>(c.position)];
      lo = glm::min(lo, p);
      hi = glm::max(hi, p);
    }
  }
  const glm::vec3 extent = hi - lo;
  const float largest = std::max({extent.x, extent.y, extent.z});
  if (!(largest > 0.0f) || !std::isfinite(largest)) fail("{}: the model has no extent (all its vertices coincide or are not finite)", context);
  glm::vec3 scale;
  for (int axis = 0; axis < 3; ++axis) {
    const bool flat = extent[axis] <= kFlatFraction * largest;
    scale[axis] = flat ? 1.0f : size_m[axis] / extent[axis];
    if (flat) warnings.push_back(std::string("flat along ") + "xyz"[axis] + ": kept at its own thickness");
  }
  ModelTransform transform;
  const glm::mat3 scaling(glm::vec3(scale.x, 0, 0), glm::vec3(0, scale.y, 0), glm::vec3(0, 0, scale.z));
  transform.linear = scaling * rotation;
  const glm::vec3 anchor(0.5f * (lo.x + hi.x), lo.y, 0.5f * (lo.z + hi.z));  // bottom centre
  transform.offset = -(scale * anchor);
  return transform;
}

void apply_transform(const ModelTransform& transform, ObjSoup& soup) {
  for (glm::vec3& p : soup.positions) p = transform.point(p);
  const glm::mat3 normal_matrix = glm::transpose(glm::inverse(transform.linear));
  for (glm::vec3& n : soup.normals) {
    const glm::vec3 m = normal_matrix * n;
    const float length2 = glm::dot(m, m);
    n = length2 > kMinLength2 ? m / std::sqrt(length2) : glm::vec3(0.0f);  // zero: regenerated later
  }
  if (transform.flips_winding()) {
    for (ObjTriangle& t : soup.triangles) std::swap(t.corners[1], t.corners[2]);
  }
}

}  // namespace phyir::scenes
