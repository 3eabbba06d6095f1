#pragma once
// Differential rendering (Debevec 1998): the view's background plus what the object changes on
// its support surface, in linear HDR. Per pixel:
//   object visible (in the with-object render, nearer than the surface-only render and than
//   the view's own surface there):        the with-object render itself;
//   support surface visible where it coincides with the view's surface (same depth within the
//   tolerance, normal within kSupportNormalToleranceDegrees): background x with / without,
//   per channel (background + (with - without) where without is 0);
//   anything else:                        the background, untouched.
// The ratio is Debevec's differential with the local surface's reflectance calibrated per pixel
// so that its surface-only render equals the background (his local scene's albedo is fitted to
// the photograph the same way): one base colour for the whole disc cannot match a textured or
// unevenly lit floor, and the plain difference then darkens a dim pixel past black wherever the
// disc alone is brighter than the image (docs/insert.md "Compositing").
#include <glm/glm.hpp>

#include "phyir/core/image.h"

namespace phyir::insert {

// A render of the local scene: colour, and its AOV depth and geometry mask.
struct LocalRender {
  Image color, depth, mask;
};

struct Composite {
  Image color;  // RGB linear HDR
  Image mask;   // Y: 1 on the object
};

// How much nearer than the view's surface the local scene may be and still count as in front:
// the support disc lies on that surface, so its depth equals the view's up to float rounding.
inline constexpr float kDepthToleranceMetres = 0.01f;
inline constexpr float kDepthToleranceRelative = 0.01f;

// The view's surface is the support surface's only where their normals agree this well: at a
// table's edge the front face lies at the disc's depth too.
inline constexpr float kSupportNormalToleranceDegrees = 25.0f;

// `view_depth`, `view_normal`: the view's depth.exr (0 = nothing) and normal.exr;
// `support_normal`: the support surface's unit normal.
Composite differential_composite(const Image& background, const Image& view_depth, const Image& view_normal,
                                 const glm::vec3& support_normal, const LocalRender& with_object,
                                 const LocalRender& without_object);

}  // namespace phyir::insert
