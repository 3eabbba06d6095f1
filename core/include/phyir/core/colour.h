#pragma once
// Colour management through OpenColorIO, with the config shipped in config/phyir.ocio.
// Used for decoding sRGB textures / LDR inputs and for making LDR previews of HDR images.
#include <filesystem>
#include <string>

#include "phyir/core/image.h"

namespace phyir {

// The OCIO config in use: $PHYIR_OCIO_CONFIG if set, else the repository's
// config/phyir.ocio. Throws phyir::Error naming the path when it cannot be loaded.
std::filesystem::path ocio_config_path();

// sRGB-encoded values (colour textures, LDR panoramas) to scene-linear Rec.709, in place.
// Only the first three channels are converted; alpha and extra channels stay as they are.
void srgb_to_linear(Image& image);

// Scene-linear HDR to an 8-bit-ready display image in [0,1]: multiply by 2^exposure_stops
// (an OCIO ExposureContrastTransform), then the config's sRGB display with `view`
// ("Standard" or "Raw"). Returns RGB (3 channels).
Image linear_to_display(const Image& linear, float exposure_stops, const std::string& view = "Standard");

}  // namespace phyir
