#include "probe_pass_schedule.h"

#include <cmath>

#include "phyir/render/streams.h"

namespace phyir::render {

ProbeSettings pass_settings(const ProbeSettings& base, int k) {
  if (k == 0) return base;
  ProbeSettings s = base;
  s.seed = stream_key(base.seed, Purpose::kProbeRefinePass, uint64_t(k));
  if (!base.progressive) return s;
  const float shrink = float(std::pow(double(k + 1), -1.0 / 3.0));
  s.cache.cell_size = base.cache.cell_size * shrink;
  s.cache.direct_distance_cells = base.cache.direct_distance_cells / shrink;
  s.sharing.parallax_texels = base.sharing.parallax_texels * shrink;
  s.chain_end_paths = 1.0f - shrink * shrink;
  return s;
}

}  // namespace phyir::render
