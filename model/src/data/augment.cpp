// Yaw rotation, mirroring and exposure jitter of a view (augment.h).
#include "augment.h"

#include <numeric>

#include "phyir/core/error.h"
#include "phyir/core/pcg32.h"

namespace phyir::model {

namespace {

// The augmentation's random stream, apart from torch's generator (initialisation, the
// rendering layer) and the epoch shuffle, so augmenting never changes their numbers.
constexpr uint64_t kAugmentStream = 0x61756730;  // "aug0"

// Columns a shift of steps / divisions of a turn moves an axis of `width` pixels.
int64_t columns(int64_t width, int steps, int divisions) {
  if (width % divisions != 0) fail("augment: width {} is not a multiple of {} rotation steps", width, divisions);
  return width / divisions * steps;
}

torch::Tensor roll_columns(const torch::Tensor& x, int steps, int divisions, int64_t dim) {
  return x.defined() ? torch::roll(x, columns(x.size(dim), steps, divisions), dim) : x;
}

torch::Tensor flip_if_defined(const torch::Tensor& x, std::vector<int64_t> dims) { return x.defined() ? x.flip(dims) : x; }

}  // namespace

int yaw_divisions(const ModelConfig& c) {
  return std::gcd(std::gcd(c.input_width, c.render_width), c.probe_width);
}

AugmentDraw draw_augment(const AugmentOptions& o, int divisions, uint64_t seed, int epoch, size_t view) {
  Pcg32 rng(mix64(seed ^ mix64(kAugmentStream)), mix64((static_cast<uint64_t>(epoch) << 32) ^ view));
  const uint32_t steps = rng.below(static_cast<uint32_t>(divisions));
  const bool mirror = rng.chance(0.5f);
  const double u = rng.uniform();
  AugmentDraw d;
  if (!o.enabled) return d;
  if (o.rotate) d.yaw_steps = static_cast<int>(steps);
  d.mirror = o.mirror && mirror;
  d.exposure_stops = o.exposure_min_stops + (o.exposure_max_stops - o.exposure_min_stops) * u;
  return d;
}

torch::Tensor rotate_about_y(const torch::Tensor& n, double turns) {
  const double a = 2.0 * M_PI * turns, c = std::cos(a), s = std::sin(a);
  const torch::Tensor x = n[0], y = n[1], z = n[2];
  return torch::stack({x * c - z * s, y, x * s + z * c}, 0);
}

// The view's per-pixel maps ([C, H, W]): what a rotation rolls and a mirror flips as images.
static torch::Tensor ViewTensors::*const kPixelMaps[] = {
    &ViewTensors::image,     &ViewTensors::depth,         &ViewTensors::normal,           &ViewTensors::base_color,
    &ViewTensors::roughness, &ViewTensors::metalness,     &ViewTensors::mask,             &ViewTensors::mask_emissive,
    &ViewTensors::mask_transparent, &ViewTensors::color_lo, &ViewTensors::render_mask, &ViewTensors::probe_mask};

// The view's per-probe-texel maps ([Hr, Wr, h, w, C]): the probes and their standard error,
// which must move and turn together.
static torch::Tensor ViewTensors::*const kProbeMaps[] = {&ViewTensors::probes, &ViewTensors::probe_stderr};

ViewTensors rotate_view(const ViewTensors& v, int steps, int divisions) {
  steps = ((steps % divisions) + divisions) % divisions;
  if (steps == 0) return v;
  ViewTensors r = v;
  for (torch::Tensor ViewTensors::*const m : kPixelMaps)
    r.*m = roll_columns(v.*m, steps, divisions, -1);
  r.normal = rotate_about_y(r.normal, static_cast<double>(steps) / divisions);
  // Probes [Hr, Wr, h, w, 3]: each moves with its pixel, and its texels (a world-aligned
  // equirect image) turn with the world.
  for (torch::Tensor ViewTensors::*const m : kProbeMaps)
    r.*m = roll_columns(roll_columns(v.*m, steps, divisions, 1), steps, divisions, 3);
  return r;
}

ViewTensors mirror_view(const ViewTensors& v) {
  ViewTensors r = v;
  for (torch::Tensor ViewTensors::*const m : kPixelMaps)
    r.*m = flip_if_defined(v.*m, {-1});
  r.normal = r.normal * torch::tensor({-1.0f, 1.0f, 1.0f}, r.normal.options()).view({3, 1, 1});
  for (torch::Tensor ViewTensors::*const m : kProbeMaps) r.*m = flip_if_defined(v.*m, {1, 3});
  return r;
}

ViewTensors expose_view(const ViewTensors& v, double stops, view::RadianceUnits units) {
  if (stops == 0.0) return v;
  ViewTensors r = v;
  const double f = std::exp2(stops);
  r.image = reexpose_ldr(v.image, f, v.exposure.raw_view());
  if (units == view::RadianceUnits::kAbsolute) return r;
  r.color_lo = v.color_lo * f;
  for (torch::Tensor ViewTensors::*const m : kProbeMaps)
    if ((v.*m).defined()) r.*m = v.*m * f;
  return r;
}

ViewTensors augment_view(const ViewTensors& v, const AugmentDraw& d, int divisions, view::RadianceUnits units) {
  ViewTensors r = rotate_view(v, d.yaw_steps, divisions);
  if (d.mirror) r = mirror_view(r);
  return expose_view(r, d.exposure_stops, units);
}

ViewTensors augment_for_epoch(const ViewTensors& view, size_t index, const AugmentOptions& options, int divisions,
                              uint64_t seed, int epoch, view::RadianceUnits units) {
  if (!options.enabled) return view;
  return augment_view(view, draw_augment(options, divisions, seed, epoch, index), divisions, units);
}

Batch augmented_batch(const std::vector<ViewTensors>& views, const std::vector<size_t>& indices,
                      const AugmentOptions& options, int divisions, uint64_t seed, int epoch, view::RadianceUnits units) {
  std::vector<ViewTensors> augmented;
  for (size_t i : indices) augmented.push_back(augment_for_epoch(views[i], i, options, divisions, seed, epoch, units));
  return collate(augmented);
}

}  // namespace phyir::model
