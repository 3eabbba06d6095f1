#include "phyir/render/probe_study_breakdown.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include "phyir/render/probe_renderer.h"

namespace phyir::render {

namespace {

// Squared errors of a strip against the reference, summed per texel over channels.
struct TexelErrors {
  std::vector<double> squared;  // per texel (strip pixel)
  double mean_reference = 0.0;  // mean |reference| over texels and channels
};

TexelErrors texel_errors(const Image& a, const Image& reference) {
  TexelErrors e;
  e.squared.assign(size_t(a.width) * size_t(a.height), 0.0);
  double sum_ref = 0.0;
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x)
      for (int ch = 0; ch < 3; ++ch) {
        const double d = double(a.at(x, y, ch)) - double(reference.at(x, y, ch));
        e.squared[size_t(y) * size_t(a.width) + size_t(x)] += d * d;
        sum_ref += std::abs(double(reference.at(x, y, ch)));
      }
  e.mean_reference = sum_ref / (3.0 * double(e.squared.size()));
  return e;
}

// The strip pixel of texel t of subset probe k, as an index into TexelErrors::squared.
size_t strip_index(const ProbeLayout& layout, size_t subset_count, size_t k, int t) {
  const int r = t / layout.res_width, c = t % layout.res_width;
  return size_t(r) * size_t(layout.res_width) * subset_count + k * size_t(layout.res_width) + size_t(c);
}

}  // namespace

const char* texel_class_name(TexelClass texel_class) {
  static constexpr const char* kNames[kTexelClassCount] = {
      "sky/environment",      "emitter",         "glass", "glossy (rough < 0.3)",
      "behind (own surface)", "diffuse < 0.5 m", "diffuse >= 0.5 m"};
  return kNames[texel_class];
}

std::vector<int> classify_texels(const RenderScene& scene, const std::vector<ProbeSite>& sites,
                                 const std::vector<int>& subset, const ProbeLayout& layout, float glossy) {
  const int h = layout.res_height, w = layout.res_width;
  std::vector<int> classes(subset.size() * size_t(h * w));
  for (size_t k = 0; k < subset.size(); ++k) {
    const ProbeSite& site = sites[size_t(subset[k])];
    for (int r = 0; r < h; ++r) {
      for (int c = 0; c < w; ++c) {
        const glm::vec3 d = probe_texel_direction(r, c, h, w, glm::vec2(0.5f));
        SurfaceInteraction si;
        int cls = kFar;
        if (!scene.trace(Ray{site.origin, d}, &si)) cls = kSky;
        else if (si.emits) cls = kEmitter;
        else if (si.transmission > 0.0f) cls = kGlass;
        else if (si.brdf.roughness < glossy) cls = kGlossy;
        else if (glm::dot(d, site.normal) < 0.0f) cls = kBehind;
        else if (si.distance < kNearTexelDistance) cls = kNear;
        classes[k * size_t(h * w) + size_t(r * w + c)] = cls;
      }
    }
  }
  return classes;
}

Image probe_strip(const Image& mosaic, const ProbeLayout& layout, const std::vector<int>& subset) {
  Image out(layout.res_width * int(subset.size()), layout.res_height, mosaic.channels);
  for (size_t k = 0; k < subset.size(); ++k) {
    const Image probe = probe_image(mosaic, layout, subset[k] / layout.grid_width, subset[k] % layout.grid_width);
    for (int r = 0; r < layout.res_height; ++r)
      for (int c = 0; c < layout.res_width; ++c)
        for (int ch = 0; ch < mosaic.channels; ++ch) out.at(int(k) * layout.res_width + c, r, ch) = probe.at(c, r, ch);
  }
  return out;
}

// Error by texel class and by probe: each one's share of the squared error and its RMSE
// relative to the whole subset's mean |reference| (so the classes' squared values add up to
// the total's). With `other` (the same setting, another seed) and the reference's halves, the
// error splits into what does not average away between seeds (bias) and noise.
nlohmann::json error_breakdown(const Image& measured, const Image* other, const Image& reference, const Image halves[2],
                               const std::vector<int>& classes, const std::vector<int>& subset,
                               const std::vector<ProbeSite>& sites, const ProbeLayout& layout,
                               const RenderScene& scene) {
  const TexelErrors e = texel_errors(measured, reference);
  const TexelErrors half = texel_errors(halves[0], halves[1]);
  std::optional<TexelErrors> pair;
  if (other) pair = texel_errors(measured, *other);
  const int texels = layout.texels_per_probe();
  const double n_all = double(e.squared.size()) * 3.0, scale = e.mean_reference;
  double total = 0.0;
  for (double s : e.squared) total += s;
  struct Sum {
    double err = 0, noise = 0, ref_noise = 0, signed_err = 0, ref = 0;
    size_t count = 0;
    Sum& operator+=(const Sum& o) {
      err += o.err, noise += o.noise, ref_noise += o.ref_noise, signed_err += o.signed_err, ref += o.ref;
      count += o.count;
      return *this;
    }
  };
  std::vector<Sum> per_class(kTexelClassCount), per_probe(subset.size());
  for (size_t k = 0; k < subset.size(); ++k) {
    for (int t = 0; t < texels; ++t) {
      const size_t i = strip_index(layout, subset.size(), k, t);
      const int x = int(i % size_t(measured.width)), y = int(i / size_t(measured.width));
      for (Sum* s : {&per_class[size_t(classes[k * size_t(texels) + size_t(t)])], &per_probe[k]}) {
        s->err += e.squared[i];
        s->ref_noise += half.squared[i] / 4.0;  // the mean of two halves: (h0 - h1)^2 / 4
        if (pair) s->noise += pair->squared[i] / 2.0;  // one run's variance
        for (int ch = 0; ch < 3; ++ch) {
          s->signed_err += double(measured.at(x, y, ch)) - double(reference.at(x, y, ch));
          s->ref += double(reference.at(x, y, ch));
        }
        ++s->count;
      }
    }
  }
  auto describe = [&](const Sum& s) {
    nlohmann::json j = {{"texels", s.count}, {"share_of_squared_error", total > 0 ? s.err / total : 0.0},
                        {"relative_rmse", std::sqrt(s.err / n_all) / scale},
                        {"reference_noise", std::sqrt(s.ref_noise / n_all) / scale},
                        {"mean_error_of_own_mean", s.ref > 0 ? s.signed_err / s.ref : 0.0}};
    if (pair) {
      j["noise"] = std::sqrt(s.noise / n_all) / scale;
      j["bias"] = std::sqrt(std::max(s.err - s.noise - s.ref_noise, 0.0) / n_all) / scale;
    }
    return j;
  };
  nlohmann::json out = {{"classes", nlohmann::json::object()}, {"probes", nlohmann::json::array()}};
  for (int c = 0; c < kTexelClassCount; ++c)
    out["classes"][texel_class_name(TexelClass(c))] = describe(per_class[size_t(c)]);
  for (size_t k = 0; k < subset.size(); ++k) {
    const ProbeSite& site = sites[size_t(subset[k])];
    nlohmann::json j = describe(per_probe[k]);
    j["index"] = subset[k];
    j["normal"] = {site.normal.x, site.normal.y, site.normal.z};
    j["nearest_light_m"] = scene.emitters().distance_bound(site.origin);
    out["probes"].push_back(j);
  }
  Sum total_sum;
  for (const Sum& c : per_class) total_sum += c;
  out["total"] = describe(total_sum);
  return out;
}

}  // namespace phyir::render
