#include "phyir/core/image_error.h"

#include <algorithm>
#include <cmath>

#include "phyir/core/error.h"

namespace phyir {

ImageError image_error(const Image& a, const Image& b, const Image* mask) {
  if (a.width != b.width || a.height != b.height)
    fail("image_error: sizes differ ({}x{} vs {}x{})", a.width, a.height, b.width, b.height);
  if (mask && (mask->width != a.width || mask->height != a.height))
    fail("image_error: mask size {}x{} differs from the images' {}x{}", mask->width, mask->height, a.width, a.height);
  const int channels = std::min({a.channels, b.channels, 3});
  double sum_sq = 0.0, sum_abs = 0.0, sum_ref = 0.0;
  size_t count = 0;
  for (int y = 0; y < a.height; ++y) {
    for (int x = 0; x < a.width; ++x) {
      if (mask && mask->at(x, y) == 0.0f) continue;
      for (int c = 0; c < channels; ++c) {
        const double d = double(a.at(x, y, c)) - double(b.at(x, y, c));
        sum_sq += d * d;
        sum_abs += std::abs(d);
        sum_ref += std::abs(double(b.at(x, y, c)));
      }
      ++count;
    }
  }
  ImageError e;
  e.pixels = count;
  if (count == 0) return e;
  const double n = double(count) * channels;
  e.rmse = std::sqrt(sum_sq / n);
  e.mean_abs = sum_abs / n;
  e.relative_rmse = sum_ref > 0.0 ? e.rmse / (sum_ref / n) : 0.0;
  return e;
}

}  // namespace phyir
