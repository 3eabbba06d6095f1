#include "phyir/view/probe_layout.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "phyir/core/error.h"
#include "phyir/core/setting_error.h"

namespace phyir::view {

void ProbeLayout::validate() const {
  if (grid_height <= 0 || grid_width <= 0 || grid_height > 4096 || grid_width > 8192)
    fail_setting("probe.grid", "{}x{} must be between 1x1 and 4096x8192", grid_height, grid_width);
  if (res_height <= 0 || res_width <= 0 || res_height > 1024 || res_width > 2048)
    fail_setting("probe.res", "{}x{} must be between 1x1 and 1024x2048", res_height, res_width);
  const double texels = double(mosaic_width()) * double(mosaic_height());
  // One RGB float mosaic of this size is 12 bytes per texel; 2^31 texels would be 24 GB.
  if (mosaic_width() > 1 << 20 || mosaic_height() > 1 << 20 || texels > double(1u << 31))
    fail_setting("probe.grid", "{}x{} with probes of {}x{} texels makes a {}x{} mosaic, too large to hold",
                 grid_height, grid_width, res_height, res_width, mosaic_height(), mosaic_width());
}

void nearest_cell(int i, int j, int ci, int cj, int grid_height, int grid_width, int* oi, int* oj) {
  const double v = (i + 0.5) / ci, u = (j + 0.5) / cj;
  *oi = std::min(grid_height - 1, static_cast<int>(std::floor(v * grid_height)));
  *oj = std::min(grid_width - 1, static_cast<int>(std::floor(u * grid_width)));
}

void parse_size(const std::string& text, const std::string& setting, int* height, int* width) {
  std::istringstream in(text);
  int h = 0, w = 0;
  char x = 0;
  if (!(in >> h >> x >> w) || (x != 'x' && x != 'X') || !in.eof())
    fail_setting(setting, "'{}' is not HxW (two positive integers, e.g. 16x32)", text);
  *height = h;
  *width = w;
}

}  // namespace phyir::view
