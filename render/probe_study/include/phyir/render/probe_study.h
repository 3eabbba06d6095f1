#pragma once
// What per-pixel light probes cost and how wrong they are, per mode and setting, against a
// converged reference (docs/probes-accuracy.md, "Accuracy and cost"; `phyir bench probes` runs it and
// writes the tables). The path tracer's studies are render/studies.h.
//
// The reference is the unbiased path mode at `reference_spp` on a subset of valid probes
// (random, or given; computed ones in a room that is all light), rendered as two independent
// halves so that its own noise is measured too: reference noise = RMSE(half 1 - half 2) / 2,
// relative like the errors. Each setting is then timed and compared on that subset: cache mode
// renders the full grid (its cache depends on every probe); path mode renders the subset only
// and its time is scaled to the grid's probe count (its probes are independent; the row says
// `extrapolated`). Where two settings differ in their seed alone, the error splits into bias
// and noise (probe_study_breakdown.h).
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "phyir/core/image.h"
#include "phyir/core/image_error.h"
#include "phyir/render/effects.h"
#include "phyir/render/probe_calibration.h"
#include "phyir/render/probe_renderer.h"
#include "phyir/render/probe_study_spread.h"

namespace phyir::render {

struct ProbeStudyOptions {
  std::string scene;               // named in messages
  ProbeSettings base;              // layout, offset, path, seed, photons: every setting starts from it
  int reference_spp = 16384;       // relative noise 1.2% on the mini room (docs/probes-accuracy.md)
  int reference_probes = 16;       // random valid probes the error is measured on
  std::vector<int> probe_indices;  // these instead (i * grid width + j), to study one probe
  bool subset_only = false;        // cache mode too renders only the subset (its cache then sees only it)
};

// One setting to measure: its name in the tables and the probes' settings.
struct ProbeStudySetting {
  std::string name;
  ProbeSettings settings;
};

struct ProbeStudyRow {
  ProbeStudySetting setting;
  double seconds = 0.0;      // for the full grid (scaled from the subset when extrapolated)
  double cpu_seconds = 0.0;  // the process's CPU seconds, scaled the same way
  double rays = 0.0;         // scaled the same way
  bool extrapolated = false;
  ImageError error;          // against the reference, on the subset
  ProbeSpread per_probe;     // each subset probe's relative RMSE, median and 90th percentile
  ProbeCalibration calibration;  // its standard error against its actual error (probe_calibration.h)
  ProbeStats stats;
  Image strip;               // the subset's probes side by side (probe_strip)
  Image strip_stderr;        // their texels' standard errors, laid out as `strip`
};

// Two settings that differ in their seed alone: their runs tell noise from bias.
bool same_but_seed(const ProbeSettings& a, const ProbeSettings& b);

class ProbeStudy {
 public:
  // Places the grid's probes (options.base's layout) and picks the subset. Throws
  // phyir::SettingError for bad settings or probe indices.
  ProbeStudy(const RenderScene& scene, const CameraModel& camera, const Effects& effects, ProbeStudyOptions options);

  const std::vector<int>& subset() const { return subset_; }
  int computed_probes() const { return computed_; }  // of the full grid (not kNothing)
  // "<grid>_<resolution>_<spp>spp_<n>probes_seed<seed>" (or "_probes-<i>-<j>..." for given
  // indices): names the reference's files.
  const std::string& tag() const { return tag_; }
  // The subset's probes: index, grid cell, origin and normal.
  nlohmann::json subset_json() const;

  // The reference's halves: read from `cache` (reference_<tag>_half<h>.exr) when there, else
  // rendered and written there.
  void make_reference(const std::filesystem::path& cache);
  double reference_noise() const { return reference_noise_; }
  // The reference's own noise per probe (its halves' difference / 2, relative to each probe's
  // mean |reference|), as ProbeStudyRow::per_probe is the error.
  const ProbeSpread& reference_noise_per_probe() const { return reference_noise_per_probe_; }
  // The reference (mean of the halves) and its halves, as strips (make_reference first).
  const Image& reference() const { return reference_; }
  const Image& reference_half(int h) const { return halves_[h]; }
  const ProbeLayout& layout() const { return options_.base.layout; }

  // One setting, timed and compared with the reference (make_reference first).
  ProbeStudyRow measure(const ProbeStudySetting& setting) const;

  // Where `row`'s error is; `other`: the same setting under another seed, or null.
  nlohmann::json breakdown(const ProbeStudyRow& row, const ProbeStudyRow* other) const;

 private:
  void pick_subset();

  const RenderScene& scene_;
  const Effects& effects_;
  ProbeStudyOptions options_;
  std::vector<ProbeSite> sites_;
  int computed_ = 0;  // probes a full-grid render computes
  std::vector<int> subset_;
  std::string tag_;
  Image halves_[2];
  Image half_stderr_[2];     // the halves' standard errors (empty when read from an older cache)
  Image reference_;
  Image reference_stderr_;   // the reference's: sqrt(s0^2 + s1^2) / 2
  double reference_noise_ = 0.0;
  ProbeSpread reference_noise_per_probe_;
  std::vector<int> classes_;  // texel classes of the subset (classify_texels)
};

}  // namespace phyir::render
