#include "phyir/insert/differential_composite.h"

#include <algorithm>
#include <cmath>

#include "phyir/core/error.h"

namespace phyir::insert {

namespace {

float tolerance(float view) { return kDepthToleranceMetres + kDepthToleranceRelative * view; }

// Whether a local surface at `local` metres is in front of (or on) the view's at `view`.
bool in_front(float local, float view) { return !(view > 0.0f) || local <= view + tolerance(view); }

// Whether the support disc at `local` metres is the view's own surface there: where the disc
// overhangs that surface (past a table's edge) it stands for nothing in the image, and its
// change would darken whatever lies behind.
bool on_surface(float local, float view) { return view > 0.0f && std::abs(local - view) <= tolerance(view); }

// The background changed by what the object does to the support surface there.
float calibrated_difference(float background, float with, float without) {
  if (without > 0.0f) return background * (with / without);
  return std::max(0.0f, background + (with - without));
}

}  // namespace

Composite differential_composite(const Image& background, const Image& view_depth, const Image& view_normal,
                                 const glm::vec3& support_normal, const LocalRender& with_object,
                                 const LocalRender& without_object) {
  const int w = background.width, h = background.height;
  for (const Image* i : {&view_depth, &view_normal, &with_object.color, &with_object.depth, &without_object.color,
                         &without_object.depth})
    if (i->width != w || i->height != h) fail("differential composite: images of different sizes");
  const float min_cos = std::cos(glm::radians(kSupportNormalToleranceDegrees));
  const auto facing = [&](int x, int y) {
    const glm::vec3 n(view_normal.at(x, y, 0), view_normal.at(x, y, 1), view_normal.at(x, y, 2));
    return glm::dot(n, support_normal) >= min_cos;
  };
  Composite out;
  out.color = Image(w, h, 3);
  out.mask = Image(w, h, 1);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const float vd = view_depth.at(x, y, 0);
      const bool hit = with_object.mask.at(x, y, 0) > 0.5f, surface = without_object.mask.at(x, y, 0) > 0.5f;
      const float d = with_object.depth.at(x, y, 0);
      // The object: seen where the surface-only render sees nothing or something farther.
      const bool object = hit && (!surface || d < without_object.depth.at(x, y, 0) - 1e-4f) && in_front(d, vd);
      out.mask.at(x, y, 0) = object ? 1.0f : 0.0f;
      const bool support = !object && surface && on_surface(without_object.depth.at(x, y, 0), vd) && facing(x, y);
      for (int c = 0; c < 3; ++c) {
        const float bg = background.at(x, y, c);
        float v = bg;
        if (object) {
          v = with_object.color.at(x, y, c);
        } else if (support) {
          v = calibrated_difference(bg, with_object.color.at(x, y, c), without_object.color.at(x, y, c));
        }
        out.color.at(x, y, c) = v;
      }
    }
  return out;
}

}  // namespace phyir::insert
