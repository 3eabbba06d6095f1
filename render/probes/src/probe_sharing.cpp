#include "probe_sharing.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cmath>

#include "phyir/core/error.h"
#include "phyir/core/safe_math.h"

namespace phyir::render {

namespace {

// One surface: ~25 degrees between normals (a 0.5 m sphere turns 6 degrees between probes
// 5 cm apart); the tangent-plane tolerance separates a table top from the floor under it.
constexpr float kMinNormalCos = 0.9f;
constexpr float kPlaneSlope = 0.1f;
constexpr float kPlaneSlack = 0.002f;  // metres: the origins' float noise is far below
// Hit distances further apart than this factor mean an occluder one probe sees and the other not.
constexpr float kMaxDistanceRatio = 2.0f;

bool one_surface(const ProbeSite& a, const ProbeSite& b, float max_baseline) {
  const glm::vec3 d = b.origin - a.origin;
  const float len = std::sqrt(glm::dot(d, d));
  if (!(len <= max_baseline)) return false;
  if (!(glm::dot(a.normal, b.normal) >= kMinNormalCos)) return false;
  const float slack = kPlaneSlope * len + kPlaneSlack;
  return std::abs(glm::dot(a.normal, d)) <= slack && std::abs(glm::dot(b.normal, d)) <= slack;
}

// Values further apart than this many standard errors of their difference see different light
// (parallax moved an edge or a halo); 2 refuses neighbours that differ by noise.
constexpr double kConsistentErrors = 3.0;

bool consistent(const glm::dvec3& a, const glm::dvec3& b, float variance_a, float variance_b) {
  const double d = double(luminance(glm::vec3(a))) - double(luminance(glm::vec3(b)));
  return d * d <= kConsistentErrors * kConsistentErrors * (double(variance_a) + double(variance_b));
}

bool similar_distances(float a, float b) {
  if (std::isinf(a) || std::isinf(b)) return std::isinf(a) && std::isinf(b);
  return std::max(a, b) <= kMaxDistanceRatio * std::min(a, b);
}

// Per texel: its centre direction and the largest parallax angle there (texels narrow at the poles).
struct TexelParallax {
  std::vector<glm::vec3> centre;
  std::vector<float> max_angle;
};

TexelParallax texel_parallax(const ProbeLayout& layout, float parallax_texels) {
  const int h = layout.res_height, w = layout.res_width, texels = layout.texels_per_probe();
  TexelParallax tp{std::vector<glm::vec3>(static_cast<size_t>(texels)), std::vector<float>(static_cast<size_t>(texels))};
  for (int t = 0; t < texels; ++t) {
    const int row = t / w;
    tp.centre[size_t(t)] = probe_texel_direction(row, t % w, h, w, glm::vec2(0.5f));
    const float width = kTwoPi / float(w) * std::sin(kPi * (float(row) + 0.5f) / float(h));
    tp.max_angle[size_t(t)] = parallax_texels * std::min(kPi / float(h), width);
  }
  return tp;
}

void check_records(const ProbeLayout& layout, const TexelRecords& records) {
  const size_t records_needed = size_t(layout.probe_count()) * size_t(layout.texels_per_probe());
  if (records.distance.size() != records_needed || records.samples.size() != records_needed ||
      records.variance.size() != records_needed ||
      (!records.cache_variance.empty() && records.cache_variance.size() != records_needed))
    fail("sharing needs texel records of {} texels, {} given", records_needed, records.samples.size());
}

// What every probe's average reads.
struct SharingInputs {
  const Image& mosaic;
  const ProbeLayout& layout;
  const std::vector<ProbeSite>& sites;
  const std::vector<uint8_t>& computed;
  const TexelRecords& records;
  const ProbeSharing& sharing;
  const TexelParallax& parallax;

  bool usable(int p) const { return computed[size_t(p)] && sites[size_t(p)].valid(); }
  double cache_sigma(size_t id) const {
    return records.cache_variance.empty() ? 0.0 : std::sqrt(std::max(double(records.cache_variance[id]), 0.0));
  }
  glm::dvec3 texel(int probe, int t) const {
    const glm::ivec2 at = layout.mosaic_pixel(probe, t);
    return glm::dvec3(mosaic.at(at.x, at.y, 0), mosaic.at(at.x, at.y, 1), mosaic.at(at.x, at.y, 2));
  }
};

// One probe's texels averaged with its window's; one per thread, buffers reused.
class WindowAverage {
 public:
  explicit WindowAverage(const SharingInputs& in)
      : in_(in),
        texels_(in.layout.texels_per_probe()),
        sum_(static_cast<size_t>(texels_)),
        weight_(static_cast<size_t>(texels_)),
        weighted_variance_(static_cast<size_t>(texels_)),
        weighted_cache_sigma_(static_cast<size_t>(texels_)),
        took_(static_cast<size_t>(texels_)) {}

  // Writes probe p's shared texels into `out` and their standard errors into `error`
  // (if not null); returns how many took in a neighbour.
  uint64_t share(int p, Image& out, Image* error) {
    start_from_own(p);
    take_in_window(p);
    return write_shared(p, out, error);
  }

 private:
  void start_from_own(int p) {
    const size_t base_p = size_t(p) * size_t(texels_);
    for (int t = 0; t < texels_; ++t) {
      const double n = in_.records.samples[base_p + size_t(t)];
      sum_[size_t(t)] = n * in_.texel(p, t);
      weight_[size_t(t)] = n;
      weighted_variance_[size_t(t)] = n * n * double(in_.records.variance[base_p + size_t(t)]);
      weighted_cache_sigma_[size_t(t)] = n * in_.cache_sigma(base_p + size_t(t));
      took_[size_t(t)] = 0;
    }
  }

  // Every usable probe of the (2r+1) x (2r+1) window on p's surface.
  void take_in_window(int p) {
    const ProbeLayout& layout = in_.layout;
    const int r = in_.sharing.radius;
    const int i = p / layout.grid_width, j = p % layout.grid_width;
    for (int di = -r; di <= r; ++di) {
      for (int dj = -r; dj <= r; ++dj) {
        const int qi = i + di, qj = j + dj;
        if ((di == 0 && dj == 0) || qi < 0 || qj < 0 || qi >= layout.grid_height || qj >= layout.grid_width) continue;
        const int q = qi * layout.grid_width + qj;
        if (!in_.usable(q) || !one_surface(in_.sites[size_t(p)], in_.sites[size_t(q)], in_.sharing.max_baseline))
          continue;
        take_in_neighbour(p, q);
      }
    }
  }

  // Probe q's texels that see what p's see: similar distances, small parallax, consistent values.
  void take_in_neighbour(int p, int q) {
    const TexelRecords& records = in_.records;
    const glm::vec3 baseline = in_.sites[size_t(q)].origin - in_.sites[size_t(p)].origin;
    const size_t base_p = size_t(p) * size_t(texels_), base_q = size_t(q) * size_t(texels_);
    for (int t = 0; t < texels_; ++t) {
      const float dp = records.distance[base_p + size_t(t)], dq = records.distance[base_q + size_t(t)];
      if (!similar_distances(dp, dq)) continue;
      const glm::vec3& dir = in_.parallax.centre[size_t(t)];
      const glm::vec3 across = baseline - glm::dot(baseline, dir) * dir;
      if (!(std::sqrt(glm::dot(across, across)) <= in_.parallax.max_angle[size_t(t)] * std::min(dp, dq))) continue;
      const glm::dvec3 value = in_.texel(q, t);
      if (!consistent(in_.texel(p, t), value, records.variance[base_p + size_t(t)],
                      records.variance[base_q + size_t(t)]))
        continue;
      const double n = records.samples[base_q + size_t(t)];
      sum_[size_t(t)] += n * value;
      weight_[size_t(t)] += n;
      weighted_variance_[size_t(t)] += n * n * double(records.variance[base_q + size_t(t)]);
      weighted_cache_sigma_[size_t(t)] += n * in_.cache_sigma(base_q + size_t(t));
      took_[size_t(t)] = 1;
    }
  }

  // Variance of a weighted mean of independent estimates, sum n^2 var / (sum n)^2 (own streams and
  // interleaved strata), plus the cache's error, which neighbours looking at one surface read alike.
  uint64_t write_shared(int p, Image& out, Image* error) const {
    uint64_t shared = 0;
    for (int t = 0; t < texels_; ++t) {
      if (!took_[size_t(t)]) continue;
      ++shared;
      const double weight = weight_[size_t(t)];
      const glm::dvec3 v = sum_[size_t(t)] / weight;
      const glm::ivec2 at = in_.layout.mosaic_pixel(p, t);
      for (int ch = 0; ch < 3; ++ch) out.at(at.x, at.y, ch) = float(v[ch]);
      const double own = std::max(weighted_variance_[size_t(t)], 0.0) / (weight * weight);
      const double cache = weighted_cache_sigma_[size_t(t)] / weight;
      if (error) error->at(at.x, at.y, 0) = float(std::sqrt(own + cache * cache));
    }
    return shared;
  }

  const SharingInputs& in_;
  int texels_;
  std::vector<glm::dvec3> sum_;
  std::vector<double> weight_;
  std::vector<double> weighted_variance_;  // sum of n^2 x variance
  std::vector<double> weighted_cache_sigma_;  // sum of n x the cache's standard error
  std::vector<uint8_t> took_;
};

}  // namespace

glm::ivec2 sub_stratum(int i, int j, const ProbeSharing& sharing) {
  const int n = sharing.window();
  return glm::ivec2(j % n, i % n);
}

Image share_between_neighbours(const Image& mosaic, const ProbeLayout& layout, const std::vector<ProbeSite>& sites,
                               const std::vector<uint8_t>& computed, const TexelRecords& records,
                               const ProbeSharing& sharing, uint64_t* shared_texels, Image* standard_error) {
  Image out = mosaic;
  if (sharing.radius <= 0) return out;
  check_records(layout, records);
  const TexelParallax parallax = texel_parallax(layout, sharing.parallax_texels);
  const SharingInputs in{mosaic, layout, sites, computed, records, sharing, parallax};
  std::atomic<uint64_t> shared{0};
  tbb::parallel_for(tbb::blocked_range<int>(0, layout.probe_count(), 16), [&](const tbb::blocked_range<int>& range) {
    WindowAverage average(in);
    uint64_t local_shared = 0;
    for (int p = range.begin(); p < range.end(); ++p)
      if (in.usable(p)) local_shared += average.share(p, out, standard_error);
    shared += local_shared;
  });
  if (shared_texels) *shared_texels = shared.load();
  return out;
}

}  // namespace phyir::render
