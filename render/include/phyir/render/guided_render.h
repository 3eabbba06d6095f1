#pragma once
// A view's colour with path guiding (docs/guiding.md), trained as Müller et al. 2017 do
// (section 5.2): passes of 1, 2, 4, ... paths per pixel, each sampling with the SD-tree the
// passes before it trained and recording into the next one; the last pass takes the rest of
// the budget and records nothing. The image averages every pass's samples with equal weight
// per sample: each pass is unbiased given its tree, and fixed weights keep the sum unbiased.
//
// Determinism: tiles are handed out in order and their records merged into the tree in tile
// order (guiding/ordered_record_merge.h), so the same seed gives the same image for any
// thread count. The sample numbers run on across passes (pass k's first sample follows pass
// k-1's last), so no two passes share random streams.
#include <cstdint>
#include <vector>

#include <nlohmann/json.hpp>

#include "phyir/render/camera.h"
#include "phyir/render/effects.h"
#include "phyir/render/film.h"
#include "phyir/render/guiding/sd_tree.h"
#include "phyir/render/path_counters.h"
#include "phyir/render/render_scene.h"

namespace phyir::render {

struct GuidingSettings {
  bool enabled = false;
  float bsdf_fraction = 0.5f;  // a: the BRDF's share of the mixture, in (0, 1] (the paper's 0.5)
  guiding::SDTreeSettings tree;
  void validate() const;       // SettingError naming "guiding.bsdf_fraction", ...
};

struct GuidingStats {
  bool ran = false;
  std::vector<int> pass_spp;      // paths per pixel of each pass, the last one untrained
  guiding::SDTreeStats tree;      // the tree the last pass sampled
  double training_seconds = 0.0;  // rebuilding the tree between passes (records merge while tracing)
  nlohmann::json to_json(const GuidingSettings& settings) const;
};

// The passes' sample counts for a budget of `spp`: 1, 2, 4, ..., 2^(K-1), then the rest, at
// least 2^K (so the last pass, the best guided, holds about half the samples).
std::vector<int> guiding_passes(int spp);

struct RenderSettings;

// Renders `film`'s colour with guiding (settings.guiding), counting into *counters.
GuidingStats render_color_guided(const RenderScene& scene, const CameraModel& camera, const RenderSettings& settings,
                                 const Effects& effects, Film* film, PathCounters* counters);

}  // namespace phyir::render
