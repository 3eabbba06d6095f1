#pragma once
// One view's probes being rendered: the steps of ProbeRenderer::render_at, in the order of
// docs/probes-estimator.md, "Code map". The light transport the probes share is its
// ViewTransport (probe_view_transport.h); passes and sharing in probe_view.cpp, texels in
// probe_view_texels.cpp. Internal to the probe renderer.
#include <utility>
#include <vector>

#include <tbb/enumerable_thread_specific.h>

#include "phyir/core/progress.h"
#include "foot_correction.h"
#include "phyir/render/probe_renderer.h"
#include "probe_sharing.h"
#include "probe_view_transport.h"

namespace phyir::render {

class ProbeView {
 public:
  // `earlier_choices`: the texel choices of earlier passes over these probes (the most any
  // made); a texel is supersampled where its own first look or they chose it.
  ProbeView(const RenderScene& scene, const Effects& effects, const ProbeSettings& settings,
            std::vector<ProbeSite> sites, const std::vector<int>& subset,
            const std::vector<uint8_t>* earlier_choices = nullptr);
  ProbeOutput run();

 private:
  struct TexelState;
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
    std::vector<TexelState> texels;  // the pass's texels between their first samples and their value
  };
  // One thread's working memory and statistics.
  struct Worker {
    ProbeStats stats;
    std::vector<glm::vec2> strata;
    std::vector<float> luminances;  // of one estimate's samples, in the strata's order
    std::vector<std::pair<uint64_t, float>> cache_errors;  // of one estimate's samples: (block, sigma)
    std::vector<EmitterCoverage::View::Piece> pieces;
    std::vector<TileProbe> tile;
    std::vector<std::pair<uint64_t, glm::vec3>> emission_seen;  // added after sharing
    std::vector<std::pair<uint64_t, glm::vec3>> photon_light;   // the photons' estimates, added after sharing
    std::vector<glm::vec3> photon_radiance, photon_radiance_cos;  // one probe's, PunctualPhotons::gather
    std::vector<float> photon_scale;                             // its texels' (0: not in the pass)
  };
  // A texel being shaded.
  struct Texel {
    TileProbe* probe = nullptr;
    int t = 0, row = 0, col = 0;
    ProbeTexel cone{0, 0, 1, 1};
    FootIrradiance* measure = nullptr;  // where its cosine-weighted light goes (pass 0 of the correction)
    float distance = 0.0f;              // its nearest hit
    glm::vec3 cos_all{0.0f}, cos_emitted{0.0f};
    int samples = 0;          // directions its value (apart from the emission seen directly) took
    float variance = 0.0f;    // of that value's luminance (ProbeView::estimate), from its own samples
    float cache_variance = 0.0f;  // what the cache's fill noise adds to it (shared with other texels)
    // Photons counted as this x their number: spp / its directions where balanced, else 1.
    float photon_scale = 1.0f;
  };
  using Part = TexelEstimator::Part;
  // A texel between its first samples and its final value.
  struct TexelState {
    Texel x;
    bool looked = false;       // its first samples are in (it is in the pass being shaded)
    Part part = Part::kAll;    // kRest where a light's emission is estimated apart
    glm::vec3 first{0.0f};     // mean of the first samples (final where `done`)
    float spread = 0.0f;       // their luminances' range
    uint8_t seen = 0;          // TexelEstimator::Seen: they met glass, a glossy surface or a light
    bool done = false;         // a light's outline: supersampled from the start
    glm::vec3 exact{0.0f};     // the emission seen directly, estimated apart
    glm::vec3 exact_cos{0.0f}; // its cosine-weighted mean (FootIrradiance)
    glm::vec3 value{0.0f};     // its final value but the emission seen directly (finish_texel)
  };

  void select_probes();
  void shade_pass(int pass);
  void shade_tile(const std::vector<size_t>& tile, int pass, Worker* w);
  void prepare_probe(TileProbe* probe, int pass) const;
  // A texel's first spp samples (and a lit texel's emission seen directly), then its value:
  // them, or a hard texel's hard_spp fresh ones.
  void first_look(TileProbe& probe, int t, int pass, Worker* w);
  void finish_texel(TileProbe& probe, int t, Worker* w);
  // The tile's extra directions to its probes' texels in proportion to their noise per direction.
  void balance(Worker* w);
  // A texel estimated again from `share` fresh directions where that is at least twice its own.
  void rebalance(TexelState& s, double share, Worker* w);
  // A hard texel from hard_spp fresh samples (kSkySppFactor x spp where it saw the sky), or
  // kDeepSppFactor x as many where those spread widely.
  glm::vec3 hard_estimate(TexelState& s, Worker* w);
  // The largest difference between a plain texel's first value and its neighbours' (luminance).
  float neighbour_step(const TileProbe& probe, int t) const;
  // A lit texel's emission seen directly; true (value final) where a light's outline crosses it.
  bool look_at_light(TexelState& s, Worker* w);
  glm::vec3 estimate(Texel& x, int first, int count, Part part, uint8_t* seen, float* spread, Worker* w);
  void store_texel(const Texel& x, glm::vec3 value, const glm::vec3& seen_emission, Worker* w);
  // The photons' estimate of the pass's texels (punctual_photons.h), kept to be added after
  // sharing; pass 0's also go into the foot correction's measure now.
  void gather_photons(TileProbe& probe, int pass, Worker* w);
  // A texel's cosine-weighted light into its probe's foot measure (pass 0 of the correction).
  void measure_texel(TexelState& s) const;
  void add_after_sharing(const std::vector<std::pair<uint64_t, glm::vec3>> Worker::*list);
  void correct_feet();
  void share_between_neighbours();

  bool in_pass(const TileProbe& probe, int t, int pass) const;
  // The choice a texel's own samples make, kept for later passes; and the earlier passes'.
  void note_choice(const Texel& x, TexelChoice choice);
  TexelChoice earlier_choice(const Texel& x) const;
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
  ProbeTiles tiles_;
  ViewTransport transport_;
  TexelCones cones_;
  TexelRecords records_;
  std::vector<FootCorrection> feet_;
  glm::vec3 common_difference_{0.0f};
  tbb::enumerable_thread_specific<Worker> workers_;
  const std::vector<uint8_t>* earlier_ = nullptr;
  Progress* progress_ = nullptr;  // during run()
};

}  // namespace phyir::render
