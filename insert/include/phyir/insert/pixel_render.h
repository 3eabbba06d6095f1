#pragma once
// Rendering only the pixels an insertion uses. A composite reads the local renders where their
// geometry is (the object and its disc: a few percent of the panorama), and the bench scores
// the truth over that region; the rest of a full render would be thrown away. Each pixel here
// is summed from the same keyed streams as render::render_view's (render::sum_pixel_samples),
// so its value is bit-identical to the full render's, whatever the thread count.
#include <vector>

#include <glm/glm.hpp>

#include "phyir/core/image.h"
#include "phyir/render/render_view.h"

namespace phyir::insert {

// The pixels of `mask` (channel 0 at least 0.5) and those within `margin` pixels of one (a
// square neighbourhood; columns wrap round the panorama, rows stop at its edges), row by row.
std::vector<glm::ivec2> dilated_pixels(const Image& mask, int margin);

// Sets `color` (RGB, the camera's size) at `pixels` to render_view's colour there with `settings`
// (its spp, seed and path settings; guiding is not supported: phyir::Error); other pixels are
// left as they are.
void render_pixels(const render::RenderScene& scene, const render::CameraModel& camera,
                   const render::RenderSettings& settings, const std::vector<glm::ivec2>& pixels, Image& color);

}  // namespace phyir::insert
