#pragma once
// A float image in memory: row-major, interleaved channels, row 0 at the top.
#include <cstddef>
#include <cstdint>
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

// 8-bit code values as an image file stores them (0-255, not yet scaled to [0,1]): row-major,
// interleaved channels, row 0 at the top. A quarter of an Image's memory.
struct ByteImage {
  int width = 0;
  int height = 0;
  int channels = 0;
  std::vector<uint8_t> codes;
};

}  // namespace phyir
