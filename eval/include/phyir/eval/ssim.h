#pragma once
// SSIM (Wang et al. 2004) with a Gaussian window, in plain C++ (no torch), for eq. 7's
// probe metric. The defaults are the training loss's definition (model/src/training/losses.cpp):
// 5x5 window (radius 2), sigma 1.5, C1 = (0.01)^2, C2 = (0.03)^2 (data range 1), population
// (co)variances, CirP padding (wrap around the columns: a probe is an equirect image whose
// left and right edges meet; replicate the rows), SSIM averaged over every texel and channel.
// Other paddings and a crop exist so the tests can reproduce skimage's definition exactly.
#include "phyir/core/image.h"

namespace phyir::eval {

enum class Padding { kReplicate, kWrap, kReflect };  // kReflect = scipy's "reflect" (d c b a | a b c d)

struct SsimOptions {
  int radius = 2;
  double sigma = 1.5;
  double c1 = 1e-4, c2 = 9e-4;
  Padding rows = Padding::kReplicate;
  Padding columns = Padding::kWrap;
  int crop = 0;  // border pixels left out of the mean (skimage crops (win_size - 1) / 2)
  // If set (one channel, the images' size), the mean is over the pixels where it is above 0.5
  // (the windows still read their neighbours outside it); NaN where it has none.
  const Image* region = nullptr;
};

// Mean SSIM over channels and (cropped) pixels of two images of the same size.
double ssim(const Image& x, const Image& y, const SsimOptions& options = {});

}  // namespace phyir::eval
