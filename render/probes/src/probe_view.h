#pragma once
// One view's probes being rendered: the steps of ProbeRenderer::render_at (docs/probes.md,
// "The two modes"). Internal to the probe renderer.
//
//   select_probes         which probes are computed; their position, normal and mask images
//   build_cache           discovery rays from every texel, then the radiance cache's fill
//   shade_pass            every tile in parallel (twice with the foot correction: the texels
//                         that may look to the front, then those facing the probe's surface)
//     shade_tile          a tile's probes texel by texel across the tile
//       shade_texel       one texel: its first samples, then the hard texels' extra samples
//   correct_feet          the cache's error at each probe's foot, less the common part
//   share_between_neighbours  texels averaged with neighbouring probes' on one surface
#include <memory>
#include <utility>
#include <vector>

#include <tbb/enumerable_thread_specific.h>

#include "phyir/core/progress.h"
#include "emitter_coverage.h"
#include "emitter_footprints.h"
#include "foot_correction.h"
#include "phyir/render/probe_renderer.h"
#include "probe_sharing.h"
#include "probe_texel_estimator.h"
#include "radiance_cache.h"

namespace phyir::render {

class ProbeView {
 public:
  ProbeView(const RenderScene& scene, const Effects& effects, const ProbeSettings& settings,
            std::vector<ProbeSite> sites, const std::vector<int>& subset);
  ProbeOutput run();

 private:
  // A probe of the tile being shaded: what its texels share.
  struct TileProbe {
    size_t k = 0;  // index into todo_
    int p = 0;     // index into the grid
    Interleave interleave;         // interleaved strata when texels are shared
    std::vector<uint8_t> lit;      // texels a light may cover (EmitterFootprints)
    EmitterCoverage::View lights;  // the lights' exact coverage, where `analytic`
    bool analytic = false;
    FootIrradiance measured{glm::vec3(0.0f, 0.0f, 1.0f)};
    FootCorrection foot;
  };
  // One thread's working memory and statistics.
  struct Worker {
    ProbeStats stats;
    std::vector<glm::vec2> strata;
    std::vector<EmitterCoverage::View::Piece> pieces;
    std::vector<TileProbe> tile;
    std::vector<std::pair<uint64_t, glm::vec3>> emission_seen;  // added after sharing
  };
  // A texel being shaded.
  struct Texel {
    TileProbe* probe;
    int t, row, col;
    ProbeTexel cone;
    FootIrradiance* measure;  // where its cosine-weighted light goes (pass 0 of the correction)
    float distance;           // its nearest hit
    glm::vec3 cos_all{0.0f}, cos_emitted{0.0f};
  };
  using Part = TexelEstimator::Part;

  void select_probes();
  void build_cache();
  void shade_pass(int pass);
  void shade_tile(const std::vector<size_t>& tile, int pass, Worker* w);
  void prepare_probe(TileProbe* probe, int pass) const;
  void shade_texel(TileProbe& probe, int t, int pass, Worker* w);
  // A texel's `part` from spp samples, or from hard_spp fresh ones where those were hard;
  // `exact` is the light the texel has apart from them (the emission seen directly).
  glm::vec3 shade_rest(Texel& x, Part part, const glm::vec3& exact, Worker* w, bool* supersampled);
  // A lit texel's light: the emission seen directly apart, the rest by shade_rest (from
  // hard_spp samples from the start where a light's outline crosses the texel).
  glm::vec3 shade_lit_texel(Texel& x, Worker* w, glm::vec3* seen_emission, bool* supersampled);
  // The mean of `count` fresh samples from sample id `first` on, stratified over the texel.
  glm::vec3 estimate(Texel& x, int first, int count, Part part, bool* saw_hard, float* spread, Worker* w);
  void store_texel(const Texel& x, glm::vec3 value, const glm::vec3& seen_emission, bool supersampled, Worker* w);
  void correct_feet();
  void share_between_neighbours();

  bool in_pass(const TileProbe& probe, int t, int pass) const;
  uint64_t texel_id(int probe, int texel) const { return uint64_t(probe) * uint64_t(texels_) + uint64_t(texel); }

  const RenderScene& scene_;
  const Effects& effects_;
  const ProbeSettings& settings_;
  const ProbeLayout& layout_;
  const int texels_;
  const uint64_t probe_seed_;
  const bool adaptive_, share_, correct_foot_;
  ProbeOutput out_;
  std::vector<int> todo_;
  std::vector<std::vector<size_t>> tiles_;
  std::unique_ptr<RadianceCache> cache_;
  std::unique_ptr<TexelEstimator> estimator_;
  EmitterFootprints footprints_;
  EmitterCoverage coverage_;
  TexelCones cones_;
  float dark_floor_ = 0.0f;
  TexelRecords records_;
  std::vector<FootCorrection> feet_;
  glm::vec3 common_difference_{0.0f};
  tbb::enumerable_thread_specific<Worker> workers_;
  Progress* progress_ = nullptr;  // during run()
};

}  // namespace phyir::render
