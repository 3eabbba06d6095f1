#include "phyir/eval/figure.h"

#include <algorithm>

#include "phyir/core/colour.h"
#include "phyir/core/image_io.h"
#include "phyir/core/image_resample.h"

namespace phyir::eval {
namespace {

constexpr int kTileW = 256, kTileH = 128, kGap = 4;

Image rgb(const Image& image) { return take_channels(image, 3, "figure tile"); }

Image scaled(const Image& image, float scale, float offset = 0.0f) {
  Image out = rgb(image);
  for (float& v : out.pixels) v = std::clamp(v * scale + offset, 0.0f, 1.0f);
  return out;
}

// Pastes `tile` (any size, area-resized to fit kTileW x kTileH) at grid cell (row, col).
void paste(Image& canvas, const Image& tile, int row, int col) {
  const Image t = area_resize(rgb(tile), kTileW, kTileH);
  const int x0 = kGap + col * (kTileW + kGap), y0 = kGap + row * (kTileH + kGap);
  for (int y = 0; y < kTileH; ++y)
    for (int x = 0; x < kTileW; ++x)
      for (int c = 0; c < 3; ++c) canvas.at(x0 + x, y0 + y, c) = std::clamp(t.at(x, y, c), 0.0f, 1.0f);
}

// The three spheres side by side on a black tile of the tile's aspect ratio.
Image sphere_strip(const std::vector<RelitSphere>& spheres, float exposure) {
  Image strip(kTileW, kTileH, 3);
  const int side = std::min(kTileW / 3, kTileH);
  for (size_t k = 0; k < spheres.size() && k < 3; ++k) {
    const Image s = area_resize(linear_to_display(spheres[k].color, exposure, "Standard"), side, side);
    const int x0 = int(k) * side, y0 = (kTileH - side) / 2;
    for (int y = 0; y < side; ++y)
      for (int x = 0; x < side; ++x)
        for (int c = 0; c < 3; ++c) strip.at(x0 + x, y0 + y, c) = s.at(x, y, c);
  }
  return strip;
}

}  // namespace

void write_side_by_side(const std::filesystem::path& file, const GroundTruthView& gt, const ViewImages& p) {
  const int rows = 7, cols = 3;
  Image canvas(kGap + cols * (kTileW + kGap), kGap + rows * (kTileH + kGap), 3, 0.15f);
  const float ev = gt.exposure_stops;
  float max_depth = 1e-3f;
  for (float d : gt.depth.pixels) max_depth = std::max(max_depth, d);
  const float inv_depth = 1.0f / max_depth;

  paste(canvas, gt.input, 0, 0);
  paste(canvas, linear_to_display(gt.color, ev, "Standard"), 0, 1);
  if (p.rerender) paste(canvas, linear_to_display(*p.rerender, ev, "Standard"), 0, 2);
  paste(canvas, linear_to_display(gt.basecolor, 0.0f, "Standard"), 1, 1);
  if (p.basecolor) paste(canvas, linear_to_display(*p.basecolor, 0.0f, "Standard"), 1, 2);
  paste(canvas, scaled(gt.normal, 0.5f, 0.5f), 2, 1);
  if (p.normal) paste(canvas, scaled(*p.normal, 0.5f, 0.5f), 2, 2);
  paste(canvas, scaled(gt.depth, inv_depth), 3, 1);
  if (p.depth) paste(canvas, scaled(*p.depth, inv_depth), 3, 2);
  paste(canvas, scaled(gt.roughness, 1.0f), 4, 1);
  if (p.roughness) paste(canvas, scaled(*p.roughness, 1.0f), 4, 2);
  paste(canvas, scaled(gt.metalness, 1.0f), 5, 1);
  if (p.metalness) paste(canvas, scaled(*p.metalness, 1.0f), 5, 2);
  if (!p.spheres_gt.empty()) {
    paste(canvas, sphere_strip(p.spheres_gt, ev), 6, 1);
    paste(canvas, sphere_strip(p.spheres_pred, ev), 6, 2);
  }
  write_image(file, canvas);
}

}  // namespace phyir::eval
