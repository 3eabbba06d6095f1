#pragma once
// How close an insertion is to the true render, over a region of the panorama (the object and
// its support surface: its shadow and reflection), and how its shading moves along a path.
#include <vector>

#include <glm/glm.hpp>

#include "phyir/core/image.h"

namespace phyir::insert {

// eval's masked MSE (pixel_metrics.h) and SSIM (ssim.h: Gaussian window of radius 2, sigma
// 1.5, C1 = 0.01^2, C2 = 0.03^2 for data in [0, 1], rows replicated, columns wrapped round the
// panorama) over the pixels where `region` (channel 0) is above 0.5; SSIM is meant for
// display-encoded images. Sizes differ or not RGB: phyir::Error; an empty region: NaN.
double masked_rmse(const Image& a, const Image& b, const Image& region);
double masked_ssim(const Image& a, const Image& b, const Image& region);

// The mean colour over the region (zero for an empty region).
glm::dvec3 masked_mean(const Image& image, const Image& region);

// Temporal consistency along a path: the frame-to-frame changes of a shading descriptor (e.g.
// the object's mean colour) of the composites against the truth's, root mean square over the
// steps and channels of (composite change - true change). Both lists one entry per frame, the
// same length (at least 2), else phyir::Error.
double change_error(const std::vector<glm::dvec3>& composite, const std::vector<glm::dvec3>& truth);
// The root mean square frame-to-frame change itself (the scale change_error is read against).
double rms_change(const std::vector<glm::dvec3>& frames);

// Mean and sample standard deviation (0 for one value) of a list of scores, NaNs left out.
struct ScoreSummary {
  double mean = 0.0, sd = 0.0;
  int count = 0;
};
ScoreSummary summarize(const std::vector<double>& scores);

}  // namespace phyir::insert
