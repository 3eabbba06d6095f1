#include "phyir/core/image_resample.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "phyir/core/error.h"

namespace phyir {
namespace {

// One output coordinate's source span: the pixels it overlaps and their overlap lengths.
struct Taps {
  std::vector<int> first;               // per output pixel, index into `index`/`weight`
  std::vector<int> index;
  std::vector<double> weight;           // overlap length / output pixel length (sums to 1)
};

Taps box_taps(int in, int out) {
  Taps t;
  const double scale = double(in) / double(out);
  for (int o = 0; o < out; ++o) {
    t.first.push_back(static_cast<int>(t.index.size()));
    const double a = o * scale, b = (o + 1) * scale;
    for (int i = static_cast<int>(std::floor(a)); i < static_cast<int>(std::ceil(b)) && i < in; ++i) {
      const double overlap = std::min(b, double(i + 1)) - std::max(a, double(i));
      if (overlap <= 1e-12) continue;
      t.index.push_back(i);
      t.weight.push_back(overlap / scale);
    }
  }
  t.first.push_back(static_cast<int>(t.index.size()));
  return t;
}

}  // namespace

Image area_resize(const Image& image, int width, int height) {
  if (width <= 0 || height <= 0 || image.empty()) fail("area_resize: bad size {}x{}", width, height);
  if (image.width == width && image.height == height) return image;
  const Taps tx = box_taps(image.width, width), ty = box_taps(image.height, height);
  const int C = image.channels;
  // Separable: rows first (into doubles), then columns.
  std::vector<double> rows(size_t(image.height) * width * C, 0.0);
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < width; ++x)
      for (int k = tx.first[x]; k < tx.first[x + 1]; ++k)
        for (int c = 0; c < C; ++c)
          rows[(size_t(y) * width + x) * C + c] += tx.weight[k] * image.at(tx.index[k], y, c);
  Image out(width, height, C);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      for (int c = 0; c < C; ++c) {
        double s = 0.0;
        for (int k = ty.first[y]; k < ty.first[y + 1]; ++k) s += ty.weight[k] * rows[(size_t(ty.index[k]) * width + x) * C + c];
        out.at(x, y, c) = static_cast<float>(s);
      }
  return out;
}

Image mask_resize(const Image& mask, int width, int height) {
  if (mask.width == width && mask.height == height) {
    Image out(width, height, 1);
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x) out.at(x, y) = mask.at(x, y, 0) > 0.5f ? 1.0f : 0.0f;
    return out;
  }
  const Taps tx = box_taps(mask.width, width), ty = box_taps(mask.height, height);
  Image out(width, height, 1);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      bool all = true;
      for (int ky = ty.first[y]; ky < ty.first[y + 1] && all; ++ky)
        for (int kx = tx.first[x]; kx < tx.first[x + 1] && all; ++kx)
          all = mask.at(tx.index[kx], ty.index[ky], 0) > 0.5f;
      out.at(x, y) = all ? 1.0f : 0.0f;
    }
  return out;
}

Image nearest_resize(const Image& image, int width, int height) {
  if (width <= 0 || height <= 0 || image.empty()) fail("nearest_resize: bad size {}x{}", width, height);
  auto source = [](int out, int in) {
    const double step = 1.0 / (double(out) / double(in));  // OpenCV's 1 / inv_scale
    std::vector<int> index(static_cast<size_t>(out));
    for (int o = 0; o < out; ++o) index[size_t(o)] = std::min(int(std::floor(o * step)), in - 1);
    return index;
  };
  const std::vector<int> sx = source(width, image.width), sy = source(height, image.height);
  Image out(width, height, image.channels);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      for (int c = 0; c < image.channels; ++c) out.at(x, y, c) = image.at(sx[size_t(x)], sy[size_t(y)], c);
  return out;
}

Size coarser(Size a, Size b) {
  return int64_t(b.width) * b.height < int64_t(a.width) * a.height ? b : a;
}

Image at_size(const Image& image, Size size) {
  if (image.width == size.width && image.height == size.height) return image;
  return area_resize(image, size.width, size.height);
}

Image take_channels(const Image& image, int channels, const std::string& what) {
  if (image.channels == channels) return image;
  if (image.channels < channels && image.channels != 1)
    fail("{}: has {} channel(s), expected {}", what, image.channels, channels);
  Image out(image.width, image.height, channels);
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x)
      for (int c = 0; c < channels; ++c) out.at(x, y, c) = image.at(x, y, image.channels == 1 ? 0 : c);
  return out;
}

}  // namespace phyir
