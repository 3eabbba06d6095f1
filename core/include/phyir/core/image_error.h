#pragma once
// Error between two images of the same size, over the first three channels, optionally
// restricted to pixels where `mask` (1 channel) is non-zero. Used by the accuracy-versus-
// time studies and tests; the evaluation suite has the paper's metrics.
#include "phyir/core/image.h"

namespace phyir {

struct ImageError {
  double rmse = 0.0;           // sqrt(mean((a - b)^2))
  double relative_rmse = 0.0;  // rmse / mean(|b|): scale-free, comparable across scenes
  double mean_abs = 0.0;
  size_t pixels = 0;
};

// `reference` is b. Throws phyir::Error when sizes differ.
ImageError image_error(const Image& estimate, const Image& reference, const Image* mask = nullptr);

}  // namespace phyir
