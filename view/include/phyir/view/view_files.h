#pragma once
// The files of a view folder (docs/conventions.md): the one place their names are spelled.
// `phyir render` writes the render outputs and render.json; `phyir dataset generate` adds
// input.png, view.json and timing.json; `phyir infer` writes a prediction folder with the
// same names for the same maps.
#include <string>
#include <vector>

namespace phyir::view {

// Render outputs (linear EXR).
inline constexpr const char* kColorFile = "color.exr";
inline constexpr const char* kDepthFile = "depth.exr";
inline constexpr const char* kNormalFile = "normal.exr";
inline constexpr const char* kBaseColorFile = "basecolor.exr";
inline constexpr const char* kRoughnessFile = "roughness.exr";
inline constexpr const char* kMetalnessFile = "metalness.exr";
inline constexpr const char* kMaskGeometryFile = "mask_geometry.exr";
inline constexpr const char* kMaskEmissiveFile = "mask_emissive.exr";
inline constexpr const char* kMaskTransparentFile = "mask_transparent.exr";
// The light probes (probe_mosaic.h).
inline constexpr const char* kProbesFile = "probes.exr";
inline constexpr const char* kProbeMaskFile = "probe_mask.exr";
inline constexpr const char* kProbePositionFile = "probe_position.exr";
inline constexpr const char* kProbeNormalFile = "probe_normal.exr";
inline constexpr const char* kProbeStderrFile = "probe_stderr.exr";  // each texel's standard error
// Display-referred images (8-bit sRGB).
inline constexpr const char* kColorPreviewFile = "color.png";  // color.exr at render.json's exposure
inline constexpr const char* kInputFile = "input.png";         // the network's input (input_exposure.h)
// Records.
inline constexpr const char* kRenderRecordFile = "render.json";  // what the render did
inline constexpr const char* kViewRecordFile = "view.json";      // the view's manifest entry (view_record.h)
inline constexpr const char* kTimingFile = "timing.json";        // wall-clock times: not checksummed
// A folder being written: rendered under this prefix and renamed into place when whole.
inline constexpr const char* kTemporaryPrefix = ".tmp-";
// A prediction's re-rendered colour and its record (`phyir infer`).
inline constexpr const char* kRerenderFile = "rerender.exr";
inline constexpr const char* kInferRecordFile = "infer.json";

// The five material and geometry maps a prediction folder must hold, in this order.
const std::vector<std::string>& prediction_map_files();

}  // namespace phyir::view
