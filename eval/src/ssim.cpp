#include "phyir/eval/ssim.h"

#include <cmath>
#include <limits>
#include <vector>

#include "phyir/core/error.h"

namespace phyir::eval {
namespace {

int pad_index(int i, int n, Padding mode) {
  switch (mode) {
    case Padding::kReplicate:
      return i < 0 ? 0 : (i >= n ? n - 1 : i);
    case Padding::kWrap:
      return ((i % n) + n) % n;
    case Padding::kReflect: {
      const int period = 2 * n;
      int k = ((i % period) + period) % period;
      return k < n ? k : period - 1 - k;
    }
  }
  return i;
}

// Separable Gaussian blur of a one-channel plane with the given paddings.
std::vector<double> blur(const std::vector<double>& plane, int w, int h, const std::vector<double>& g, int r,
                         Padding rows, Padding columns) {
  std::vector<double> tmp(plane.size()), out(plane.size());
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      double s = 0.0;
      for (int k = -r; k <= r; ++k) s += g[k + r] * plane[size_t(y) * w + pad_index(x + k, w, columns)];
      tmp[size_t(y) * w + x] = s;
    }
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      double s = 0.0;
      for (int k = -r; k <= r; ++k) s += g[k + r] * tmp[size_t(pad_index(y + k, h, rows)) * w + x];
      out[size_t(y) * w + x] = s;
    }
  return out;
}

}  // namespace

double ssim(const Image& x, const Image& y, const SsimOptions& o) {
  if (x.width != y.width || x.height != y.height || x.channels != y.channels || x.empty())
    fail("ssim: images {}x{}x{} and {}x{}x{} differ or are empty", x.width, x.height, x.channels, y.width, y.height,
         y.channels);
  if (o.radius < 0 || o.sigma <= 0.0) fail("ssim: bad window (radius {}, sigma {})", o.radius, o.sigma);
  const int w = x.width, h = x.height, r = o.radius;
  if (2 * o.crop >= w || 2 * o.crop >= h) fail("ssim: crop {} leaves nothing of {}x{}", o.crop, w, h);
  if (o.region && (o.region->width != w || o.region->height != h))
    fail("ssim: a {}x{} region for {}x{} images", o.region->width, o.region->height, w, h);
  std::vector<double> g(2 * r + 1);
  double total = 0.0;
  for (int k = -r; k <= r; ++k) total += g[k + r] = std::exp(-double(k * k) / (2.0 * o.sigma * o.sigma));
  for (double& v : g) v /= total;

  double sum = 0.0;
  long n = 0;
  const size_t N = size_t(w) * h;
  for (int c = 0; c < x.channels; ++c) {
    std::vector<double> a(N), b(N), aa(N), bb(N), ab(N);
    for (int yy = 0; yy < h; ++yy)
      for (int xx = 0; xx < w; ++xx) {
        const size_t i = size_t(yy) * w + xx;
        a[i] = x.at(xx, yy, c);
        b[i] = y.at(xx, yy, c);
        aa[i] = a[i] * a[i];
        bb[i] = b[i] * b[i];
        ab[i] = a[i] * b[i];
      }
    const auto ma = blur(a, w, h, g, r, o.rows, o.columns), mb = blur(b, w, h, g, r, o.rows, o.columns);
    const auto maa = blur(aa, w, h, g, r, o.rows, o.columns), mbb = blur(bb, w, h, g, r, o.rows, o.columns);
    const auto mab = blur(ab, w, h, g, r, o.rows, o.columns);
    for (int yy = o.crop; yy < h - o.crop; ++yy)
      for (int xx = o.crop; xx < w - o.crop; ++xx) {
        if (o.region && !(o.region->at(xx, yy, 0) > 0.5f)) continue;
        const size_t i = size_t(yy) * w + xx;
        const double sxx = maa[i] - ma[i] * ma[i], syy = mbb[i] - mb[i] * mb[i], sxy = mab[i] - ma[i] * mb[i];
        sum += ((2.0 * ma[i] * mb[i] + o.c1) * (2.0 * sxy + o.c2)) /
               ((ma[i] * ma[i] + mb[i] * mb[i] + o.c1) * (sxx + syy + o.c2));
        ++n;
      }
  }
  return n ? sum / n : std::numeric_limits<double>::quiet_NaN();
}

}  // namespace phyir::eval
