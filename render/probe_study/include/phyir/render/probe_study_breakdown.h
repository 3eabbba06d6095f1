#pragma once
// Where a probe study's error is (probe_study.h; docs/commands/bench.md, "Where the error
// is"): by texel class, from what a measured texel's centre direction sees from its probe's
// origin, and by probe; each with its share of the squared error, its RMSE relative to the
// whole subset's mean |reference| (so the classes' squares add up to the total's), the
// reference's own noise there and its mean error relative to its own mean. With a second run
// of the same setting under another seed, the error splits into what does not average away
// between seeds (bias) and noise.
#include <vector>

#include <nlohmann/json.hpp>

#include "phyir/core/image.h"
#include "phyir/render/probe_grid.h"
#include "phyir/render/render_scene.h"

namespace phyir::render {

// The first class that applies; a texel looking back at the probe's own surface is `behind`,
// near its foot.
enum TexelClass { kSky, kEmitter, kGlass, kGlossy, kBehind, kNear, kFar, kTexelClassCount };
const char* texel_class_name(TexelClass texel_class);

// Diffuse surfaces nearer than this (metres) see the probe's surroundings at large parallax.
constexpr float kNearTexelDistance = 0.5f;

// The class of every texel of the subset's probes: subset probe k's texel t at k * texels + t.
// Surfaces smoother than `glossy` (roughness) are glossy.
std::vector<int> classify_texels(const RenderScene& scene, const std::vector<ProbeSite>& sites,
                                 const std::vector<int>& subset, const ProbeLayout& layout, float glossy);

// The subset's probes side by side: probe k at columns [k w, (k+1) w).
Image probe_strip(const Image& mosaic, const ProbeLayout& layout, const std::vector<int>& subset);

// `measured` against `reference` (strips), `halves` the reference's two halves, `other` the
// same setting under another seed (null: no bias/noise split). JSON: "classes" (by name),
// "probes" (with index, normal and distance to the nearest light) and "total".
nlohmann::json error_breakdown(const Image& measured, const Image* other, const Image& reference, const Image halves[2],
                               const std::vector<int>& classes, const std::vector<int>& subset,
                               const std::vector<ProbeSite>& sites, const ProbeLayout& layout,
                               const RenderScene& scene);

}  // namespace phyir::render
