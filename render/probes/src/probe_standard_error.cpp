#include "probe_standard_error.h"

#include <cmath>

namespace phyir::render {

namespace {

// Half the texel's own variance, half its 3x3 neighbourhood's mean (the texel included).
float pooled_variance(const Image& own, int probe_x, int probe_y, int r, int c, int h, int w) {
  double sum = 0.0;
  int n = 0;
  for (int dr = -1; dr <= 1; ++dr) {
    const int rr = r + dr;
    if (rr < 0 || rr >= h) continue;
    for (int dc = -1; dc <= 1; ++dc) {
      const double s = own.at(probe_x + (c + dc + w) % w, probe_y + rr, 0);
      sum += s * s;
      ++n;
    }
  }
  const double self = own.at(probe_x + c, probe_y + r, 0);
  return float(0.5 * self * self + 0.5 * sum / n);
}

}  // namespace

Image pooled_standard_error(const Image& own, const view::ProbeLayout& layout) {
  Image out(own.width, own.height, 1);
  const int h = layout.res_height, w = layout.res_width;
  for (int i = 0; i < layout.grid_height; ++i)
    for (int j = 0; j < layout.grid_width; ++j)
      for (int r = 0; r < h; ++r)
        for (int c = 0; c < w; ++c)
          out.at(j * w + c, i * h + r, 0) = std::sqrt(pooled_variance(own, j * w, i * h, r, c, h, w));
  return out;
}

}  // namespace phyir::render
