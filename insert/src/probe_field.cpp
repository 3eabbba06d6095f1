#include "phyir/insert/probe_field.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "phyir/core/equirect.h"
#include "phyir/core/error.h"
#include "phyir/view/view_files.h"

namespace phyir::insert {

namespace {

int wrap(int j, int n) { return ((j % n) + n) % n; }

// Grid distance between cells, columns wrapping around the panorama.
float cell_distance(int i0, int j0, int i1, int j1, int width) {
  const int dj = std::abs(j0 - j1);
  const float dx = float(std::min(dj, width - dj));
  return std::hypot(float(i0 - i1), dx);
}

}  // namespace

ProbeField::ProbeField(std::shared_ptr<const view::ProbeMosaic> probes, const glm::vec3& camera)
    : mosaic_(std::move(probes)), probes_(*mosaic_), camera_(camera) {
  const view::ProbeLayout& l = probes_.layout;
  std::vector<glm::ivec2> valid;
  for (int i = 0; i < l.grid_height; ++i)
    for (int j = 0; j < l.grid_width; ++j)
      if (probes_.valid(i, j)) valid.emplace_back(i, j);
  if (valid.empty()) fail("probe_mask.exr: no valid probe in the {}x{} grid", l.grid_height, l.grid_width);
  // Nearest valid probe per cell: a brute-force search, once (grids are at most 256x512 cells,
  // and insertion asks for the few cells the object projects to; precomputing only those would
  // complicate the lookup for no measured gain).
  fallback_.resize(size_t(l.probe_count()));
  const size_t stride = std::max<size_t>(1, valid.size() / 4096);  // caps the search's cost
  for (int i = 0; i < l.grid_height; ++i)
    for (int j = 0; j < l.grid_width; ++j) {
      float best = std::numeric_limits<float>::max();
      glm::ivec2 pick = valid[0];
      for (size_t k = 0; k < valid.size(); k += stride) {
        const float d = cell_distance(i, j, valid[k].x, valid[k].y, l.grid_width);
        if (d < best) best = d, pick = valid[k];
      }
      fallback_[size_t(i) * l.grid_width + j] = probes_.valid(i, j) ? glm::ivec2(i, j) : pick;
    }
}

glm::ivec2 ProbeField::texel_of(const glm::vec3& direction) const {
  const view::ProbeLayout& l = probes_.layout;
  const glm::vec2 uv = equirect_uv(direction);
  return {std::clamp(int(uv.x * float(l.res_width)), 0, l.res_width - 1),
          std::clamp(int(uv.y * float(l.res_height)), 0, l.res_height - 1)};
}

glm::vec3 ProbeField::texel_radiance(int i, int j, const glm::ivec2& texel) const {
  const view::ProbeLayout& l = probes_.layout;
  const int x = j * l.res_width + texel.x, y = i * l.res_height + texel.y;
  const Image& m = probes_.radiance;
  return glm::max(glm::vec3(m.at(x, y, 0), m.at(x, y, 1), m.at(x, y, 2)), glm::vec3(0.0f));
}

glm::vec3 ProbeField::probe_radiance(int i, int j, const glm::vec3& direction) const {
  return texel_radiance(i, j, texel_of(direction));
}

glm::ivec2 ProbeField::cell_of(const glm::vec3& position) const {
  const view::ProbeLayout& l = probes_.layout;
  const glm::vec2 uv = equirect_uv(glm::normalize(position - camera_));
  const int j = wrap(int(std::floor(uv.x * float(l.grid_width))), l.grid_width);
  const int i = std::clamp(int(std::floor(uv.y * float(l.grid_height))), 0, l.grid_height - 1);
  return {i, j};
}

glm::ivec2 ProbeField::nearest_valid(int i, int j) const {
  return fallback_[size_t(i) * probes_.layout.grid_width + j];
}

namespace {

void check_grid_image(const Image& image, const view::ProbeLayout& l, const char* file) {
  if (image.width != l.grid_width || image.height != l.grid_height || image.channels < 3)
    fail("{}: {}x{}, but the probe grid is {}x{}", file, image.width, image.height, l.grid_width, l.grid_height);
}

glm::vec3 texel3(const Image& image, int i, int j) { return {image.at(j, i, 0), image.at(j, i, 1), image.at(j, i, 2)}; }

float local_taper(float distance, float reach) {
  if (!(reach > 0.0f)) return 1.0f;
  const float x = distance / reach;
  return x < 1.0f ? (1.0f - x * x) * (1.0f - x * x) : 0.0f;
}

}  // namespace

bool ProbeField::use_neighbourhood(const Image& positions, const glm::vec3& centre, float radius,
                                   const SupportPlane& support) {
  const view::ProbeLayout& l = probes_.layout;
  check_grid_image(positions, l, view::kProbePositionFile);
  if (support.normals) check_grid_image(*support.normals, l, view::kProbeNormalFile);
  const float min_cos = std::cos(glm::radians(kSupportNormalDegrees));
  auto on_support = [&](int i, int j, const glm::vec3& p) {
    if (!support.normals) return true;
    return glm::dot(texel3(*support.normals, i, j), support.normal) >= min_cos &&
           std::abs(glm::dot(p - centre, support.normal)) <= kSupportPlaneMetres;
  };
  std::vector<std::pair<float, LocalProbe>> near;
  for (int i = 0; i < l.grid_height; ++i)
    for (int j = 0; j < l.grid_width; ++j) {
      const glm::vec3 p = texel3(positions, i, j);
      const float d = glm::length(p - centre);
      if (probes_.valid(i, j) && d <= radius && on_support(i, j, p)) near.push_back({d, LocalProbe{{i, j}, p}});
    }
  std::sort(near.begin(), near.end(), [](const auto& a, const auto& b) {
    return a.first < b.first || (a.first == b.first && a.second.cell.x * 100000 + a.second.cell.y <
                                                            b.second.cell.x * 100000 + b.second.cell.y);
  });
  local_.clear();
  // The taper reaches zero where the set ends: at `radius`, or, when more probes are in reach
  // than kMaxLocalProbes, at the first probe left out, so that a probe entering or leaving the
  // set as the centre moves does so with zero weight (the blend is continuous along a path).
  const float reach = near.size() > kMaxLocalProbes ? near[kMaxLocalProbes].first : radius;
  for (size_t k = 0; k < near.size() && k < kMaxLocalProbes; ++k) {
    LocalProbe p = near[k].second;
    p.taper = local_taper(near[k].first, reach);
    if (p.taper > 0.0f) local_.push_back(p);
  }
  // Every probe on the edge itself (ties at `reach`): keep the nearest, untapered.
  if (local_.empty() && !near.empty()) local_.push_back(near[0].second);
  return !local_.empty();
}

void ProbeField::set_blend_power(float power) {
  if (!(power > 0.0f)) fail("probe blend power {}: must be positive", power);
  blend_power_ = power;
}

void ProbeField::set_blend_plane(const glm::vec3& normal) {
  if (ray_distance_) fail("probe blend: a blend plane and ray distances exclude each other");
  if (!(std::abs(glm::length(normal) - 1.0f) < 1e-3f)) fail("probe blend plane: the normal must be a unit vector");
  blend_plane_ = normal;
}

void ProbeField::set_support_plane(const glm::vec3& point, const glm::vec3& normal) {
  if (!(std::abs(glm::length(normal) - 1.0f) < 1e-3f)) fail("probe blend support plane: the normal must be a unit vector");
  support_point_ = point, support_normal_ = normal;
}

bool ProbeField::sees_through_support(const glm::vec3& probe, const glm::vec3& vertex, const glm::vec3& direction) const {
  return glm::dot(probe - support_point_, support_normal_) < -kSupportPlaneMetres &&
         glm::dot(probe - vertex, direction) <= 0.0f;
}

glm::vec3 ProbeField::radiance(const glm::vec3& position, const glm::vec3& direction) const {
  if (local_.empty()) return projected_radiance(position, direction);
  const glm::ivec2 texel = texel_of(direction);  // the same texel of every probe
  glm::vec3 sum(0.0f);
  float weight = 0.0f;
  for (const LocalProbe& p : local_) {
    if (ray_distance_ && sees_through_support(p.position, position, direction)) continue;
    glm::vec3 d = position - p.position;
    d -= glm::dot(d, blend_plane_) * blend_plane_;  // the foot point's offset, with a blend plane
    if (ray_distance_) d -= glm::dot(d, direction) * direction;  // the offset across the ray
    const float r2 = glm::dot(d, d) + kLocalSmoothing * kLocalSmoothing;
    const float w = p.taper * (blend_power_ == 2.0f ? 1.0f / r2 : std::pow(r2, -0.5f * blend_power_));
    sum += w * texel_radiance(p.cell.x, p.cell.y, texel);
    weight += w;
  }
  // Every probe behind the support surface (a vertex under the plane's tolerance): the nearest.
  if (!(weight > 0.0f)) return texel_radiance(local_[0].cell.x, local_[0].cell.y, texel);
  return sum / weight;
}

glm::vec3 ProbeField::projected_radiance(const glm::vec3& position, const glm::vec3& direction) const {
  const view::ProbeLayout& l = probes_.layout;
  const glm::vec3 offset = position - camera_;
  if (!(glm::dot(offset, offset) > 1e-12f)) {
    const glm::ivec2 p = nearest_valid(l.grid_height / 2, l.grid_width / 2);
    return probe_radiance(p.x, p.y, direction);
  }
  // Continuous grid coordinates: cell (i, j)'s centre is at (i + 0.5, j + 0.5).
  const glm::vec2 uv = equirect_uv(glm::normalize(offset));
  const float gx = uv.x * float(l.grid_width) - 0.5f, gy = uv.y * float(l.grid_height) - 0.5f;
  const int j0 = int(std::floor(gx)), i0 = int(std::floor(gy));
  const float fx = gx - float(j0), fy = gy - float(i0);
  const glm::ivec2 texel = texel_of(direction);
  glm::vec3 sum(0.0f);
  float weight = 0.0f;
  for (int di = 0; di < 2; ++di)
    for (int dj = 0; dj < 2; ++dj) {
      const int i = std::clamp(i0 + di, 0, l.grid_height - 1), j = wrap(j0 + dj, l.grid_width);
      const float w = (di ? fy : 1.0f - fy) * (dj ? fx : 1.0f - fx);
      if (!(w > 0.0f) || !probes_.valid(i, j)) continue;
      sum += w * texel_radiance(i, j, texel);
      weight += w;
    }
  if (weight > 0.0f) return sum / weight;
  const glm::ivec2 c = cell_of(position);
  const glm::ivec2 p = nearest_valid(c.x, c.y);
  return texel_radiance(p.x, p.y, texel);
}

Image ProbeField::local_sampling_map() const {
  if (local_.empty()) return {};
  const view::ProbeLayout& l = probes_.layout;
  Image map(l.res_width, l.res_height, 3, 0.0f);
  float total = 0.0f;
  for (const LocalProbe& p : local_) {
    const Image one = probes_.probe(p.cell.x, p.cell.y);
    for (size_t k = 0; k < map.pixels.size(); ++k) map.pixels[k] += p.taper * std::max(0.0f, one.pixels[k]);
    total += p.taper;
  }
  for (float& v : map.pixels) v /= total;
  return map;
}

glm::vec3 mean_probe_radiance(const view::ProbeMosaic& probes) {
  const view::ProbeLayout& l = probes.layout;
  double sum[3] = {0, 0, 0}, area = 0.0;
  for (int i = 0; i < l.grid_height; ++i)
    for (int j = 0; j < l.grid_width; ++j) {
      if (!probes.valid(i, j)) continue;
      for (int r = 0; r < l.res_height; ++r) {
        const double a = equirect_texel_solid_angle(r, l.res_width, l.res_height);
        for (int c = 0; c < l.res_width; ++c) {
          const int x = j * l.res_width + c, y = i * l.res_height + r;
          for (int k = 0; k < 3; ++k) sum[k] += a * std::max(0.0f, probes.radiance.at(x, y, k));
          area += a;
        }
      }
    }
  if (!(area > 0.0)) fail("probe_mask.exr: no valid probe in the {}x{} grid", l.grid_height, l.grid_width);
  return glm::vec3(float(sum[0] / area), float(sum[1] / area), float(sum[2] / area));
}

}  // namespace phyir::insert
