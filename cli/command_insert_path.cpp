// phyir insert --path: dynamic insertion, the object moved in steps along a line of pixels,
// one composite per step (frame_NNN/), a contact sheet of their PNGs (contact_sheet.png) and
// the frames as a looping GIF (path.gif).
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>

#include "command_insert_path.h"
#include "phyir/core/colour.h"
#include "phyir/core/error.h"
#include "phyir/core/image_io.h"

namespace phyir::cli {

namespace fs = std::filesystem;

namespace {

constexpr int kSheetColumns = 4;
constexpr float kAnimationFps = 4.0f;

void paste(Image& sheet, const Image& tile, int column, int row) {
  for (int y = 0; y < tile.height; ++y)
    for (int x = 0; x < tile.width; ++x)
      for (int c = 0; c < 3; ++c) sheet.at(column * tile.width + x, row * tile.height + y, c) = tile.at(x, y, c);
}

}  // namespace

void insert_along_path(const insert::InsertView& view, const scenes::Scene& object, insert::InsertRequest request,
                       glm::ivec2 from, glm::ivec2 to, int steps, const fs::path& out) {
  if (steps < 2) fail("--steps {}: a path needs at least 2 steps", steps);
  const int columns = std::min(kSheetColumns, steps), rows = (steps + columns - 1) / columns;
  Image sheet(columns * view.width(), rows * view.height(), 3);
  std::vector<Image> frames;
  for (int k = 0; k < steps; ++k) {
    const float t = float(k) / float(steps - 1);
    request.x = int(std::lround(from.x + t * float(to.x - from.x)));
    request.y = int(std::lround(from.y + t * float(to.y - from.y)));
    spdlog::info("insert --path: step {}/{} at pixel ({}, {})", k + 1, steps, request.x, request.y);
    const insert::InsertResult result = insert::insert_object(view, object, request);
    insert::write_insert_outputs(out / fmt::format("frame_{:03d}", k), view, result);
    frames.push_back(linear_to_display(result.composite.color, float(view.exposure_stops), view.display_view));
    paste(sheet, frames.back(), k % columns, k / columns);
  }
  write_image(out / "contact_sheet.png", sheet);
  write_animation(out / "path.gif", frames, kAnimationFps);
}

}  // namespace phyir::cli
