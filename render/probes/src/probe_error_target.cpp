#include "probe_error_target.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>

#include "phyir/core/safe_math.h"
#include "probe_pass_schedule.h"

namespace phyir::render {

namespace {

glm::vec3 texel_value(const Image& mosaic, const glm::ivec2& at) {
  return glm::vec3(mosaic.at(at.x, at.y, 0), mosaic.at(at.x, at.y, 1), mosaic.at(at.x, at.y, 2));
}

// The variance and luminance sums of probe p's texels.
GridError probe_error(const ProbeOutput& out, int p) {
  GridError e;
  const int texels = out.layout.texels_per_probe();
  for (int t = 0; t < texels; ++t) {
    const glm::ivec2 at = out.layout.mosaic_pixel(p, t);
    const float sigma = out.standard_error.at(at.x, at.y, 0);
    e.variance_sum += double(sigma) * sigma;
    e.luminance_sum += luminance(texel_value(out.mosaic, at));
  }
  e.texels = uint64_t(texels);
  return e;
}

// One texel that two independent passes hold, before they are merged.
void agree(const ProbeOutput& held, const ProbeOutput& added, const glm::ivec2& at, PassAgreement* agreement) {
  const double d = double(luminance(texel_value(held.mosaic, at))) - double(luminance(texel_value(added.mosaic, at)));
  const double a = held.standard_error.at(at.x, at.y, 0), b = added.standard_error.at(at.x, at.y, 0);
  if (!std::isfinite(d) || !std::isfinite(a) || !std::isfinite(b)) return;
  agreement->squared_difference += d * d;
  agreement->reported_variance += a * a + b * b;
  ++agreement->texels;
}

// `pass`'s statistics added to `total`'s, its seconds included (a later pass's time is the view's).
void add_pass_stats(const ProbeStats& pass, ProbeStats* total) {
  const uint64_t probes = total->probes, valid = total->valid, nothing = total->nothing, emitter = total->emitter,
                 transparent = total->transparent;
  *total += pass;
  // A pass counts the grid's probes again: the view's counts are the first pass's.
  total->probes = probes, total->valid = valid, total->nothing = nothing, total->emitter = emitter,
  total->transparent = transparent;
  total->cache_seconds += pass.cache_seconds;
  total->shade_seconds += pass.shade_seconds;
  total->share_seconds += pass.share_seconds;
  total->total_seconds += pass.total_seconds;
  total->cache_fill_samples += pass.cache_fill_samples;
}

}  // namespace

std::vector<int> first_passes(const ProbeOutput& out, const std::vector<int>& subset) {
  std::vector<int> passes(size_t(out.layout.probe_count()), 0);
  auto count = [&](int p) {
    const ProbeSite& site = out.sites[size_t(p)];
    if (site.computed() && site.valid()) passes[size_t(p)] = 1;
  };
  if (subset.empty())
    for (int p = 0; p < out.layout.probe_count(); ++p) count(p);
  for (int p : subset) count(p);
  return passes;
}

double PassAgreement::factor() const {
  return texels > 0 && reported_variance > 0.0 ? squared_difference / reported_variance : 1.0;
}

double GridError::relative() const {
  if (texels == 0 || !(luminance_sum > 0.0)) return 0.0;
  return std::sqrt(variance_sum / double(texels)) / (luminance_sum / double(texels));
}

GridError estimated_grid_error(const ProbeOutput& out, const std::vector<int>& passes, double factor) {
  GridError total;
  for (int p = 0; p < out.layout.probe_count(); ++p) {
    if (passes[size_t(p)] == 0) continue;
    const GridError e = probe_error(out, p);
    total.variance_sum += e.variance_sum;
    total.luminance_sum += e.luminance_sum;
    total.texels += e.texels;
  }
  total.variance_sum *= factor;
  return total;
}

std::vector<int> probes_to_check(const std::vector<int>& passes) {
  std::vector<int> valid;
  for (int p = 0; p < int(passes.size()); ++p)
    if (passes[size_t(p)] > 0) valid.push_back(p);
  if (valid.size() < size_t(kCheckEvery) * kMinCheckProbes) return valid;
  std::vector<int> check;
  for (size_t k = 0; k < valid.size(); k += kCheckEvery) check.push_back(valid[k]);
  return check;
}

std::vector<int> probes_to_refine(const ProbeOutput& out, const std::vector<int>& passes, double target,
                                  double factor) {
  const GridError total = estimated_grid_error(out, passes, factor);
  const double mean = total.texels > 0 ? total.luminance_sum / double(total.texels) : 0.0;
  const double allowed = (target * mean) * (target * mean) * double(total.texels);
  std::vector<std::pair<double, int>> reductions;  // (V / (n + 1), p)
  for (int p = 0; p < out.layout.probe_count(); ++p) {
    if (passes[size_t(p)] == 0 || passes[size_t(p)] >= kMaxErrorPasses) continue;
    const double variance = probe_error(out, p).variance_sum * factor;
    if (variance > 0.0) reductions.push_back({variance / double(passes[size_t(p)] + 1), p});
  }
  // Largest first; ties by probe index, so the choice never depends on the sort's stability.
  std::sort(reductions.begin(), reductions.end(),
            [](const auto& a, const auto& b) { return a.first != b.first ? a.first > b.first : a.second < b.second; });
  std::vector<int> chosen;
  double projected = total.variance_sum;
  for (const auto& [reduction, p] : reductions) {
    if (projected <= allowed) break;
    chosen.push_back(p);
    projected -= reduction;
  }
  std::sort(chosen.begin(), chosen.end());
  return chosen;
}

void merge_pass(const ProbeOutput& pass, const std::vector<int>& refined, std::vector<int>* passes, ProbeOutput* total,
                PassAgreement* agreement) {
  const int texels = total->layout.texels_per_probe();
  const bool weighted = !pass.texel_samples.empty() && pass.texel_samples.size() == total->texel_samples.size();
  for (int p : refined) {
    const double n = double((*passes)[size_t(p)]);
    for (int t = 0; t < texels; ++t) {
      const size_t id = size_t(p) * size_t(texels) + size_t(t);
      // Each pass weighted by its directions (equal weights without them).
      double held = n, added = 1.0;
      if (weighted && total->texel_samples[id] > 0.0f && pass.texel_samples[id] > 0.0f)
        held = total->texel_samples[id], added = pass.texel_samples[id];
      const double sum = held + added;
      const glm::ivec2 at = total->layout.mosaic_pixel(p, t);
      if (agreement) agree(*total, pass, at, agreement);
      for (int c = 0; c < 3; ++c)
        total->mosaic.at(at.x, at.y, c) =
            float((held * total->mosaic.at(at.x, at.y, c) + added * pass.mosaic.at(at.x, at.y, c)) / sum);
      const double old_sigma = total->standard_error.at(at.x, at.y, 0), new_sigma = pass.standard_error.at(at.x, at.y, 0);
      total->standard_error.at(at.x, at.y, 0) =
          float(std::sqrt(held * held * old_sigma * old_sigma + added * added * new_sigma * new_sigma) / sum);
      if (weighted) total->texel_samples[id] = float(sum);
    }
    ++(*passes)[size_t(p)];
  }
}

void refine_to_error(const ProbeSettings& settings, const std::vector<int>& subset, const ProbePass& render_pass,
                     ProbeOutput* first) {
  ProbeOutput& out = *first;
  std::vector<int> passes = first_passes(out, subset);
  ProbeErrorTarget& record = out.stats.error;
  record.target = settings.target_error;
  record.passes = 1;
  std::vector<uint8_t> choices = out.texel_choices;
  PassAgreement agreement;
  auto run_pass = [&](const ProbeSettings& pass_setup, const std::vector<int>& refine,
                      const std::vector<uint8_t>& earlier) {
    const ProbeOutput pass = render_pass(pass_setup, refine, earlier);
    for (size_t i = 0; i < choices.size() && i < pass.texel_choices.size(); ++i)
      choices[i] = std::max(choices[i], pass.texel_choices[i]);
    merge_pass(pass, refine, &passes, &out, &agreement);
    add_pass_stats(pass.stats, &out.stats);
    record.refined_probes += refine.size();
    ++record.passes;
  };
  int k = 1;
  if (settings.target_error > 0.0f) {
    const std::vector<int> check = probes_to_check(passes);
    // A replica of the first pass (its kernels, its own first look): the check measures how
    // far that pass's sigma reads.
    if (!check.empty()) {
      ProbeSettings first_kernels = settings;
      first_kernels.progressive = false;
      spdlog::info("probes: pass 2 over {} probes measures how far sigma reads from independent passes", check.size());
      run_pass(pass_settings(first_kernels, k++), check, {});
    }
  }
  for (; settings.target_error > 0.0f && k < kMaxErrorPasses; ++k) {
    const double reached = estimated_grid_error(out, passes, agreement.factor()).relative();
    // The target is a float: a float's rounding is not a reason for another pass.
    if (reached <= double(settings.target_error) * (1.0 + 1e-6)) break;
    const std::vector<int> refine = probes_to_refine(out, passes, settings.target_error, agreement.factor());
    if (refine.empty()) break;
    spdlog::info("probes: estimated error {:.4f} (sigma x {:.2f}) above the target {:.4f}: pass {} over {} probes",
                 reached, std::sqrt(agreement.factor()), settings.target_error, k + 1, refine.size());
    run_pass(pass_settings(settings, k), refine, choices);
  }
  record.estimated = estimated_grid_error(out, passes, agreement.factor()).relative();
  record.sigma_factor = std::sqrt(agreement.factor());
}

}  // namespace phyir::render
