// The target units and the sRGB curve of config/phyir.ocio in torch.
#include "exposure.h"

#include "phyir/core/error.h"

namespace phyir::model {

namespace {

// OpenColorIO's ExponentWithLinearTransform with config/phyir.ocio's parameters: the power
// curve ((x + o) / (1 + o))^g below which the tangent line through the origin takes over.
constexpr double kGamma = 2.4, kOffset = 0.055;
constexpr double kEncodedBreak = kOffset / (kGamma - 1.0);  // 0.0393: where the tangent touches

// Linear value over encoded value on the tangent segment (1 / 12.923).
double linear_slope() { return std::pow((kEncodedBreak + kOffset) / (1.0 + kOffset), kGamma) / kEncodedBreak; }

}  // namespace

view::RadianceUnits target_radiance(const ModelConfig& config) {
  if (config.target_units == "input") return view::RadianceUnits::kInput;
  if (config.target_units == "absolute") return view::RadianceUnits::kAbsolute;
  fail("target units '{}': input (x 2^exposure_stops of each view, the default) or absolute (the files' radiance)",
       config.target_units);
}

torch::Tensor srgb_decode(const torch::Tensor& encoded) {
  const torch::Tensor x = encoded.clamp_min(0.0);
  return torch::where(x > kEncodedBreak, ((x + kOffset) / (1.0 + kOffset)).pow(kGamma), x * linear_slope());
}

torch::Tensor srgb_encode(const torch::Tensor& linear) {
  const torch::Tensor y = linear.clamp(0.0, 1.0);
  const double linear_break = kEncodedBreak * linear_slope();
  return torch::where(y > linear_break, (1.0 + kOffset) * y.pow(1.0 / kGamma) - kOffset, y / linear_slope());
}

torch::Tensor reexpose_ldr(const torch::Tensor& image, double factor, bool raw_view) {
  if (raw_view) return (image * factor).clamp(0.0, 1.0);
  return srgb_encode(srgb_decode(image) * factor);
}

}  // namespace phyir::model
