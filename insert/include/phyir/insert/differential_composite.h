#pragma once
// Differential rendering (Debevec 1998): the view's background plus what the object changes on
// its support surface, in linear HDR. Per pixel:
//   object visible (in the with-object render, nearer than the surface-only render and than
//   the view's own surface there):        the with-object render itself;
//   support surface visible where it coincides with the view's surface (same depth within the
//   tolerance): background + (with - without);
//   anything else:                        the background, untouched.
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

// `view_depth`: the view's depth.exr (0 = nothing).
Composite differential_composite(const Image& background, const Image& view_depth, const LocalRender& with_object,
                                 const LocalRender& without_object);

}  // namespace phyir::insert
