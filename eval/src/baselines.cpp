#include "phyir/eval/baselines.h"

#include <cmath>

#include "phyir/core/colour.h"
#include "phyir/core/error.h"
#include "phyir/view/radiance_units.h"
#include "phyir/core/image_resample.h"

namespace phyir::eval {

BaselineStats compute_baseline_stats(const std::vector<view::ViewRecord>& records,
                                     const std::string& source) {
  BaselineStats s;
  s.source = source;
  double sums[14] = {0};  // basecolor 3, roughness, metalness, depth, normal 3, color 3, count, depth count
  double input_color[3] = {0, 0, 0};  // the colour sums in each view's input units
  Image probe_sum, input_probe_sum;
  long probes = 0;
  for (const view::ViewRecord& record : records) {
    const GroundTruthView v = load_ground_truth(record);
    const double to_input = view::radiance_scale(view::RadianceUnits::kInput, v.exposure_stops);
    for (int y = 0; y < v.color.height; ++y)
      for (int x = 0; x < v.color.width; ++x) {
        if (v.valid.at(x, y) < 0.5f) continue;
        for (int c = 0; c < 3; ++c) {
          sums[c] += v.basecolor.at(x, y, c);
          sums[6 + c] += v.normal.at(x, y, c);
          sums[9 + c] += v.color.at(x, y, c);
          input_color[c] += v.color.at(x, y, c) * to_input;
        }
        sums[3] += v.roughness.at(x, y);
        sums[4] += v.metalness.at(x, y);
        if (v.depth.at(x, y) > 0.0f) {
          sums[5] += v.depth.at(x, y);
          sums[13] += 1.0;
        }
        sums[12] += 1.0;
      }
    if (v.probes) {
      if (probe_sum.empty()) probe_sum = input_probe_sum = Image(v.probes->layout.res_width, v.probes->layout.res_height, 3);
      for (int i = 0; i < v.probes->layout.grid_height; ++i)
        for (int j = 0; j < v.probes->layout.grid_width; ++j) {
          if (!v.probes->valid(i, j)) continue;
          const Image p = at_size(v.probes->probe(i, j), {probe_sum.width, probe_sum.height});
          for (size_t k = 0; k < p.pixels.size(); ++k) {
            probe_sum.pixels[k] += p.pixels[k];
            input_probe_sum.pixels[k] += float(p.pixels[k] * to_input);
          }
          ++probes;
        }
    }
    ++s.views;
  }
  const double n = std::max(sums[12], 1.0);
  for (int c = 0; c < 3; ++c) {
    s.basecolor[c] = sums[c] / n;
    s.color[c] = sums[9 + c] / n;
    s.input_color[c] = input_color[c] / n;
  }
  s.roughness = sums[3] / n;
  s.metalness = sums[4] / n;
  s.depth = sums[13] > 0 ? sums[5] / sums[13] : 1.0;
  const double len = std::sqrt(sums[6] * sums[6] + sums[7] * sums[7] + sums[8] * sums[8]);
  if (len > 1e-9)
    for (int c = 0; c < 3; ++c) s.normal[c] = sums[6 + c] / len;
  if (probes > 0) {
    for (Image* sum : {&probe_sum, &input_probe_sum})
      for (float& v : sum->pixels) v = float(v / double(probes));
    s.probe = probe_sum;
    s.input_probe = input_probe_sum;
  }
  return s;
}

Prediction constant_mean_prediction(const BaselineStats& s, const GroundTruthView& gt, view::RadianceUnits units) {
  const int w = gt.color.width, h = gt.color.height;
  auto constant = [&](int channels, const double* values) {
    Image im(w, h, channels);
    for (size_t i = 0; i < im.pixels.size(); ++i) im.pixels[i] = float(values[i % channels]);
    return im;
  };
  Prediction p;
  p.basecolor = constant(3, s.basecolor);
  p.roughness = constant(1, &s.roughness);
  p.metalness = constant(1, &s.metalness);
  p.depth = constant(1, &s.depth);
  p.normal = constant(3, s.normal);
  // In input units the constant is the mean of the input-unit targets, handed over in this
  // view's absolute unit (evaluate_view scales it back by the view's exposure).
  const bool input = units == view::RadianceUnits::kInput;
  const double to_absolute = 1.0 / view::radiance_scale(units, gt.exposure_stops);
  double color[3];
  for (int c = 0; c < 3; ++c) color[c] = (input ? s.input_color[c] : s.color[c]) * to_absolute;
  p.rerender = constant(3, color);
  const std::optional<Image>& probe = input ? s.input_probe : s.probe;
  if (probe && gt.probes)
    p.probes = view::constant_probe_mosaic(*probe, gt.probes->layout.grid_height, gt.probes->layout.grid_width).scaled(to_absolute);
  return p;
}

Prediction input_as_basecolor_prediction(const GroundTruthView& gt) {
  Prediction p;
  Image linear = gt.input;
  srgb_to_linear(linear);
  p.basecolor = linear;
  return p;
}

}  // namespace phyir::eval
