#pragma once
// input.png: the LDR panorama the network sees, made from color.exr through OpenColorIO
// (linear_to_display: exposure, then the sRGB display's view) with an exposure chosen per
// view and recorded (settings.h, InputSettings).
#include <cstdint>
#include <filesystem>

#include <nlohmann/json.hpp>

#include "phyir/core/image.h"
#include "phyir/dataset/settings.h"

namespace phyir::dataset {

struct InputExposure {
  float stops = 0.0f;             // what input.png used: base + jitter
  float base_stops = 0.0f;        // auto exposure, or the fixed value
  float jitter_stops = 0.0f;      // this view's draw in [-jitter, +jitter]
  float percentile_value = 0.0f;  // auto: the percentile of color.exr's RGB values

  nlohmann::json to_json(const InputSettings& settings) const;
};

// Auto: base = log2(target / v) with v the `percentile` of all RGB values (sorted, index
// floor(percentile * n), clamped to n - 1), 0 when v <= 0, clamped to [-32, 32] stops.
// Jitter: jitter_stops * (2 u - 1) with u = hash_unit("phyir-dataset exposure|<view_seed>").
InputExposure choose_input_exposure(const Image& color, const InputSettings& settings, uint64_t view_seed);

// Writes input.png atomically (8-bit sRGB, RGB).
void write_input_image(const std::filesystem::path& path, const Image& color, const InputExposure& exposure,
                       const InputSettings& settings);

}  // namespace phyir::dataset
