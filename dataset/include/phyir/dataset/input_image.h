#pragma once
// input.png: the LDR panorama the network sees, made from color.exr through OpenColorIO
// (linear_to_display: exposure, then the sRGB display's view) with an exposure chosen per
// view and recorded (settings.h, InputSettings; the record: view/input_exposure.h).
#include <cstdint>
#include <filesystem>

#include <nlohmann/json.hpp>

#include "phyir/core/image.h"
#include "phyir/dataset/settings.h"
#include "phyir/view/input_exposure.h"

namespace phyir::dataset {

using view::InputExposure;

// Auto: base = log2(target / v) with v the `percentile` of all RGB values (sorted, index
// floor(percentile * n), clamped to n - 1), 0 when v <= 0, clamped to [-32, 32] stops.
// Jitter: jitter_stops * (2 u - 1) with u = hash_unit("phyir-dataset exposure|<view_seed>").
InputExposure choose_input_exposure(const Image& color, const InputSettings& settings, uint64_t view_seed);

// Writes input.png atomically (8-bit sRGB, RGB).
void write_input_image(const std::filesystem::path& path, const Image& color, const InputExposure& exposure,
                       const InputSettings& settings);

}  // namespace phyir::dataset
