#pragma once
// A float image in memory: row-major, interleaved channels, row 0 at the top.
#include <cstddef>
#include <vector>

namespace phyir {

struct Image {
  int width = 0;
  int height = 0;
  int channels = 0;
  std::vector<float> pixels;

  Image() = default;
  Image(int w, int h, int c, float fill = 0.0f)
      : width(w), height(h), channels(c), pixels(static_cast<size_t>(w) * h * c, fill) {}

  size_t index(int x, int y, int c = 0) const {
    return (static_cast<size_t>(y) * width + x) * channels + c;
  }
  float& at(int x, int y, int c = 0) { return pixels[index(x, y, c)]; }
  float at(int x, int y, int c = 0) const { return pixels[index(x, y, c)]; }
  bool empty() const { return pixels.empty(); }
};

}  // namespace phyir
