#include "phyir/core/colour.h"

#include <OpenColorIO/OpenColorIO.h>

#include <cstdlib>
#include <mutex>

#include "phyir/core/error.h"

namespace OCIO = OCIO_NAMESPACE;

namespace phyir {

namespace fs = std::filesystem;

fs::path ocio_config_path() {
  if (const char* env = std::getenv("PHYIR_OCIO_CONFIG"); env && *env) return env;
  return fs::path(PHYIR_CONFIG_DIR) / "phyir.ocio";
}

namespace {

OCIO::ConstConfigRcPtr load_config() {
  static std::mutex mutex;
  static OCIO::ConstConfigRcPtr config;
  std::lock_guard<std::mutex> lock(mutex);
  if (config) return config;
  const fs::path path = ocio_config_path();
  if (!fs::exists(path)) fail("{}: OpenColorIO config not found (set PHYIR_OCIO_CONFIG)", path.string());
  try {
    config = OCIO::Config::CreateFromFile(path.c_str());
    config->validate();
  } catch (const OCIO::Exception& e) {
    fail("{}: invalid OpenColorIO config: {}", path.string(), e.what());
  }
  return config;
}

void apply_processor(const OCIO::ConstProcessorRcPtr& processor, Image& image) {
  auto cpu = processor->getDefaultCPUProcessor();
  // OCIO processes packed RGB(A); strided access lets extra channels pass untouched.
  const ptrdiff_t pixel_stride = static_cast<ptrdiff_t>(image.channels) * sizeof(float);
  OCIO::PackedImageDesc desc(image.pixels.data(), image.width, image.height, 3,
                             OCIO::BIT_DEPTH_F32, sizeof(float), pixel_stride,
                             pixel_stride * image.width);
  cpu->apply(desc);
}

}  // namespace

void srgb_to_linear(Image& image) {
  if (image.channels < 3) {
    // Grey images: replicate through a 3-channel copy so OCIO sees RGB.
    Image rgb(image.width, image.height, 3);
    for (size_t i = 0; i < static_cast<size_t>(image.width) * image.height; ++i)
      for (int c = 0; c < 3; ++c) rgb.pixels[i * 3 + c] = image.pixels[i * image.channels];
    srgb_to_linear(rgb);
    for (size_t i = 0; i < static_cast<size_t>(image.width) * image.height; ++i)
      image.pixels[i * image.channels] = rgb.pixels[i * 3];
    return;
  }
  auto config = load_config();
  try {
    apply_processor(config->getProcessor("srgb_texture", "scene_linear"), image);
  } catch (const OCIO::Exception& e) {
    fail("OpenColorIO sRGB decode failed: {}", e.what());
  }
}

Image linear_to_display(const Image& linear, float exposure_stops, const std::string& view) {
  Image out(linear.width, linear.height, 3);
  for (size_t i = 0; i < static_cast<size_t>(linear.width) * linear.height; ++i)
    for (int c = 0; c < 3; ++c)
      out.pixels[i * 3 + c] = linear.pixels[i * linear.channels + std::min(c, linear.channels - 1)];
  auto config = load_config();
  try {
    auto group = OCIO::GroupTransform::Create();
    auto exposure = OCIO::ExposureContrastTransform::Create();
    exposure->setStyle(OCIO::EXPOSURE_CONTRAST_LINEAR);
    exposure->setExposure(exposure_stops);
    group->appendTransform(exposure);
    auto display = OCIO::DisplayViewTransform::Create();
    display->setSrc(OCIO::ROLE_SCENE_LINEAR);
    display->setDisplay("sRGB");
    display->setView(view.c_str());
    group->appendTransform(display);
    apply_processor(config->getProcessor(group), out);
  } catch (const OCIO::Exception& e) {
    fail("OpenColorIO display transform (view '{}') failed: {}", view, e.what());
  }
  return out;
}

}  // namespace phyir
