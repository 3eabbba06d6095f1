#pragma once
// Resampling images between resolutions (evaluation, docs/eval.md; probe mosaics,
// view/probe_mosaic.h). Evaluated maps are compared at the coarser of the two grids: the finer image is area-averaged onto
// it (exact box-overlap weights, any ratio), so every compared value covers the same
// solid-angle patch on both sides. Masks are resampled conservatively: a coarse pixel is
// valid only when every fine pixel it overlaps is valid (no value averaged across an
// object edge into a masked region counts).
#include <string>

#include "phyir/core/image.h"

namespace phyir {

// Area (box) resampling to width x height; for upsampling it replicates (each output pixel
// takes the overlap-weighted mean of the few source pixels it covers).
Image area_resize(const Image& image, int width, int height);

// Nearest-neighbour resampling as OpenCV's cv2.resize(..., INTER_NEAREST), which UniFuse's
// loaders use for ground-truth depth: output x reads source min(floor(x * s), in - 1) with
// s = 1 / (out / in) in double (not pixel-centre aligned: a 2x reduction keeps even pixels).
Image nearest_resize(const Image& image, int width, int height);

// Conservative mask resampling: output 1 where every overlapped source pixel is > 0.5.
Image mask_resize(const Image& mask, int width, int height);

// The resolution both sides are compared at: the one with fewer pixels (ties: `a`).
struct Size {
  int width = 0, height = 0;
};
Size coarser(Size a, Size b);

// `image` at `size`: itself when it already has it, area-resized otherwise.
Image at_size(const Image& image, Size size);

// Keeps the first `channels` channels (or repeats a single channel); `what` names the file
// in the error when the image has too few.
Image take_channels(const Image& image, int channels, const std::string& what);

}  // namespace phyir
