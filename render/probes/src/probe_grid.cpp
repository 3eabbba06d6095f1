#include "phyir/render/probe_grid.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "phyir/core/safe_math.h"
#include "phyir/render/equirect.h"
#include "phyir/render/gbuffer.h"
#include "phyir/render/ray_offset.h"

namespace phyir::render {

glm::vec2 probe_pixel_position(const ProbeLayout& layout, const CameraModel& camera, int i, int j) {
  return glm::vec2((j + 0.5f) * float(camera.width) / float(layout.grid_width),
                   (i + 0.5f) * float(camera.height) / float(layout.grid_height));
}

std::vector<ProbeSite> place_probes(const RenderScene& scene, const CameraModel& camera,
                                    const ProbeLayout& layout, float offset) {
  std::vector<ProbeSite> sites(size_t(layout.probe_count()));
  tbb::parallel_for(tbb::blocked_range<int>(0, layout.grid_height), [&](const tbb::blocked_range<int>& rows) {
    for (int i = rows.begin(); i < rows.end(); ++i) {
      for (int j = 0; j < layout.grid_width; ++j) {
        ProbeSite& site = sites[size_t(i) * layout.grid_width + j];
        const Ray ray = camera.generate_ray(probe_pixel_position(layout, camera, i, j));
        SurfaceInteraction si;
        if (!scene.trace(ray, &si, Coverage::kBlendSolid)) continue;  // kNothing, all zeros
        // The G-buffer's flags: at full resolution the mask agrees with mask_emissive, mask_transparent.
        const GBufferSample g = GBufferSample::from_hit(si);
        site.status = g.emissive > 0.0f      ? ProbeStatus::kEmitter
                      : g.transparent > 0.0f ? ProbeStatus::kTransparent
                                             : ProbeStatus::kValid;
        site.surface = si.position;
        site.normal = si.shading_normal;
        // Something nearer than the offset (a panel 2 mm off a wall): stop half way to it.
        site.offset = offset;
        if (offset > 0.0f) {
          Ray up{spawn_origin(si.position, si.geometric_normal, si.shading_normal), si.shading_normal};
          up.tmax = offset;
          Hit hit;
          if (scene.accelerator().intersect(up, &hit, Coverage::kBlendSolid)) site.offset = 0.5f * hit.t;
        }
        site.origin = si.position + site.offset * si.shading_normal;
      }
    }
  });
  return sites;
}

glm::vec3 probe_texel_direction(int row, int col, int height, int width, const glm::vec2& a) {
  return ProbeTexel(row, col, height, width).direction(a);
}

ProbeTexel::ProbeTexel(int row, int col, int height, int width)
    : cos0_(std::cos(double(kPi) * row / height)),
      cos1_(std::cos(double(kPi) * (row + 1) / height)),
      col_(float(col)),
      width_(float(width)) {}

glm::vec3 ProbeTexel::direction(const glm::vec2& a) const {
  const double cos_theta = std::clamp(cos0_ + (cos1_ - cos0_) * double(a.y), -1.0, 1.0);
  return equirect_direction((col_ + a.x) / width_, float(cos_theta), float(std::sqrt(1.0 - cos_theta * cos_theta)));
}

namespace {

// The s x t grid stratified_square draws `count` points on: s = ceil(sqrt(count)) columns,
// as few rows as hold them.
std::pair<int, int> strata_grid(int count) {
  const int s = int(std::ceil(std::sqrt(double(count))));
  return {s, (count + s - 1) / s};
}

}  // namespace

void stratified_square(int count, Rng& rng, std::vector<glm::vec2>* points, const Interleave& interleave) {
  const int n = std::max(interleave.count, 1);
  points->clear();
  if (count <= 0) return;
  const auto [s, t] = strata_grid(count);
  // Partial Fisher-Yates: the first `count` entries of a random permutation of the s t cells.
  thread_local std::vector<int> cells;
  cells.resize(size_t(s) * t);
  for (int k = 0; k < s * t; ++k) cells[k] = k;
  for (int k = 0; k < count; ++k) {
    const int pick = k + int(rng.next_u32() % uint32_t(s * t - k));
    std::swap(cells[k], cells[pick]);
    glm::vec2 jitter = rng.next_2d();
    if (n > 1) {
      const uint64_t h = mix64(interleave.key ^ mix64(uint64_t(cells[k]) + 1));
      const glm::ivec2 shift(int((h & 0xffffffffu) % uint64_t(n)), int((h >> 32) % uint64_t(n)));
      jitter = (glm::vec2((interleave.sub + shift) % n) + jitter) / float(n);
    }
    // Rounding can land a point of the last cell on 1.0; keep it inside [0,1).
    constexpr float kBelowOne = 0x1.fffffep-1f;
    points->push_back(glm::vec2(std::min((float(cells[k] % s) + jitter.x) / float(s), kBelowOne),
                                std::min((float(cells[k] / s) + jitter.y) / float(t), kBelowOne)));
  }
}

double stratified_mean_variance(const std::vector<glm::vec2>& points, const std::vector<float>& values,
                                int min_pairs) {
  const int count = int(points.size());
  if (count < 2 || values.size() != points.size()) return -1.0;
  const auto [s, t] = strata_grid(count);
  thread_local std::vector<float> cell_value;
  cell_value.assign(size_t(s) * t, std::numeric_limits<float>::quiet_NaN());
  for (int k = 0; k < count; ++k) {
    const int col = std::min(int(points[size_t(k)].x * float(s)), s - 1);
    const int row = std::min(int(points[size_t(k)].y * float(t)), t - 1);
    cell_value[size_t(row * s + col)] = values[size_t(k)];
  }
  double sum = 0.0;
  int pairs = 0;
  for (int row = 0; row < t; ++row) {
    for (int col = 0; col + 1 < s; col += 2) {
      const float a = cell_value[size_t(row * s + col)], b = cell_value[size_t(row * s + col + 1)];
      if (std::isnan(a) || std::isnan(b)) continue;
      sum += double(a - b) * double(a - b);
      ++pairs;
    }
  }
  if (pairs < min_pairs) return -1.0;
  // Each pair estimates two cells' variances: the mean's is their average over count.
  return sum / (2.0 * pairs * count);
}

}  // namespace phyir::render
