#include "phyir/render/guided_render.h"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <atomic>

#include "phyir/core/stopwatch.h"
#include "phyir/core/progress.h"
#include "phyir/core/setting_error.h"
#include "phyir/render/guiding/ordered_record_merge.h"
#include "phyir/render/path_tracer.h"
#include "phyir/render/render_view.h"

namespace phyir::render {

namespace {

constexpr int kTileSize = 16;

// One pass over the image: tile t covers pixels [16 tx, 16 tx + 16) x [16 ty, ...), tiles
// numbered row by row and handed out in that order, so their records reach `merge` (when
// training) about in order and wait little.
class GuidedPass {
 public:
  GuidedPass(const PathTracer& tracer, const CameraModel& camera, uint64_t seed, int first_sample, int spp)
      : tracer_(tracer), camera_(camera), seed_(seed), first_(first_sample), spp_(spp),
        tiles_x_((camera.width + kTileSize - 1) / kTileSize),
        tiles_(size_t((camera.height + kTileSize - 1) / kTileSize) * size_t(tiles_x_)) {}

  size_t tiles() const { return tiles_; }

  // Adds every pixel's sample sum to sums[pixel]; records into `merge` when given.
  void run(std::vector<glm::dvec3>* sums, guiding::OrderedRecordMerge* merge, PathCounters* counters,
           Progress* progress) const {
    std::atomic<size_t> next{0};
    tbb::enumerable_thread_specific<PathCounters> local;
    const int workers = tbb::this_task_arena::max_concurrency();
    tbb::parallel_for(0, workers, [&](int) {
      PathCounters& c = local.local();
      for (size_t tile = next++; tile < tiles_; tile = next++) {
        guiding::RecordBuffer records;
        shade_tile(tile, sums, merge ? &records : nullptr, &c);
        if (merge) merge->submit(tile, std::move(records));
        progress->advance();
      }
    });
    for (const PathCounters& c : local) *counters += c;
  }

 private:
  void shade_tile(size_t tile, std::vector<glm::dvec3>* sums, guiding::RecordBuffer* records, PathCounters* c) const {
    const int x0 = int(tile % size_t(tiles_x_)) * kTileSize, y0 = int(tile / size_t(tiles_x_)) * kTileSize;
    for (int y = y0; y < std::min(y0 + kTileSize, camera_.height); ++y) {
      for (int x = x0; x < std::min(x0 + kTileSize, camera_.width); ++x) {
        (*sums)[size_t(y) * camera_.width + x] +=
            sum_pixel_samples(tracer_, camera_, seed_, x, y, camera_.width, first_, spp_, c, records);
      }
    }
  }

  const PathTracer& tracer_;
  const CameraModel& camera_;
  uint64_t seed_;
  int first_, spp_, tiles_x_;
  size_t tiles_;
};

guiding::SDTree empty_tree(const RenderScene& scene, const guiding::SDTreeSettings& settings) {
  const scenes::Bounds bounds = scene.scene().compute_bounds();
  if (bounds.empty()) return guiding::SDTree(glm::vec3(0.0f), glm::vec3(0.0f), settings);
  return guiding::SDTree(bounds.min, bounds.max, settings);
}

}  // namespace

void GuidingSettings::validate() const {
  if (!(bsdf_fraction > 0.0f && bsdf_fraction <= 1.0f))
    fail_setting("guiding.bsdf_fraction", "{} must be in (0, 1]: the BRDF keeps every direction it can reach",
                 bsdf_fraction);
  tree.validate();
}

nlohmann::json GuidingStats::to_json(const GuidingSettings& settings) const {
  if (!ran) return {{"ran", false}};
  return {{"ran", true},
          {"bsdf_fraction", settings.bsdf_fraction},
          {"spatial_threshold", settings.tree.spatial_threshold},
          {"energy_threshold", settings.tree.energy_threshold},
          {"pass_spp", pass_spp},
          {"training_passes", tree.passes},
          {"spatial_leaves", tree.spatial_leaves},
          {"quadtree_nodes", tree.quadtree_nodes},
          {"max_quadtree_depth", tree.max_quadtree_depth},
          {"records", tree.records},
          {"rejected_records", tree.rejected_records},
          {"training_seconds", training_seconds}};
}

std::vector<int> guiding_passes(int spp) {
  std::vector<int> passes;
  int used = 0;
  // Pass 2^k trains while what is left after it still holds at least 2^(k+1).
  for (int n = 1; spp - used - n >= 2 * n; n *= 2) {
    passes.push_back(n);
    used += n;
  }
  if (spp - used > 0) passes.push_back(spp - used);
  return passes;
}

GuidingStats render_color_guided(const RenderScene& scene, const CameraModel& camera, const RenderSettings& settings,
                                 const Effects& effects, Film* film, PathCounters* counters) {
  settings.guiding.validate();
  GuidingStats stats;
  stats.ran = true;
  stats.pass_spp = guiding_passes(settings.spp);
  guiding::SDTree tree = empty_tree(scene, settings.guiding.tree);
  std::vector<glm::dvec3> sums(size_t(camera.width) * camera.height, glm::dvec3(0.0));
  PathSettings path = settings.path;
  path.guide_bsdf_fraction = settings.guiding.bsdf_fraction;
  const size_t tiles =
      size_t((camera.width + kTileSize - 1) / kTileSize) * size_t((camera.height + kTileSize - 1) / kTileSize);
  Progress progress("render", tiles * stats.pass_spp.size(), "tiles", settings.progress);
  int first_sample = 0;
  for (size_t k = 0; k < stats.pass_spp.size(); ++k) {
    const bool train = k + 1 < stats.pass_spp.size();
    path.guide = tree.trained() ? &tree : nullptr;  // the first pass samples the BRDF alone
    const PathTracer tracer(scene, effects, path);
    const GuidedPass pass(tracer, camera, settings.seed, first_sample, stats.pass_spp[k]);
    guiding::OrderedRecordMerge merge(&tree, pass.tiles());
    pass.run(&sums, train ? &merge : nullptr, counters, &progress);
    if (train) {
      const Stopwatch watch;
      tree.finish_pass(int(k));
      stats.training_seconds += watch.seconds();
    }
    first_sample += stats.pass_spp[k];
  }
  stats.tree = tree.stats();
  for (int y = 0; y < camera.height; ++y)
    for (int x = 0; x < camera.width; ++x)
      film->set_color(x, y, glm::vec3(sums[size_t(y) * camera.width + x] / double(settings.spp)));
  return stats;
}

}  // namespace phyir::render
