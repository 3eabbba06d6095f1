#pragma once
// The camera flags, one registration each: the image size (--width, --height) for every
// command that renders, and where the view is taken from (--camera, --camera-index,
// --projection) for `phyir render`. Defaults are the bound fields' (render/job/render_job.h);
// settings recorded in the flag registry: "size", "width", "height", "camera_position",
// "camera_index", "projection".
#include <CLI/CLI.hpp>

#include "phyir/render/render_job.h"

namespace phyir::cli {

// --width and --height (a panorama's width is twice its height); where only one is given, the
// other follows at 2:1. Sets the command's parse_complete_callback.
void add_image_size_flags(CLI::App* cmd, int& width, int& height);

// The size and --camera X,Y,Z (metres; default: the scene's camera), --camera-index and
// --projection of `job`.
void add_camera_flags(CLI::App* cmd, render::RenderJob& job);

}  // namespace phyir::cli
