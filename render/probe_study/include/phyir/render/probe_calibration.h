#pragma once
// How well a probe grid's reported standard error (ProbeOutput::standard_error) predicts its
// actual error against a reference, per texel in luminance (docs/probes.md "Per-texel
// standard error"): with e the difference and sigma = sqrt(stderr^2 + stderr_ref^2),
//   median_ratio      median(|e| / sigma) / 0.6745 (the median of |N(0, 1)|): 1 when calibrated,
//                     above 1 where the errors are larger than reported;
//   within_two_sigma  the fraction of texels with |e| <= 2 sigma (0.954 for Gaussian errors).
// Texels whose sigma is 0 (black on both sides) are left out.
#include <cstddef>

#include <nlohmann/json.hpp>

#include "phyir/core/image.h"

namespace phyir::render {

struct ProbeCalibration {
  double median_ratio = 0.0;      // NaN without texels
  double within_two_sigma = 0.0;  // NaN without texels
  size_t texels = 0;

  nlohmann::json to_json() const;
};

// `value`, `reference`: RGB images of the same probes; `value_stderr`, `reference_stderr`:
// their standard errors (channel 0 read), the same size.
ProbeCalibration probe_calibration(const Image& value, const Image& value_stderr, const Image& reference,
                                   const Image& reference_stderr);

}  // namespace phyir::render
