// Raw Embree throughput on a generated room: single rays versus 16-wide packets, closest
// hit versus occlusion.
#include <benchmark/benchmark.h>

#include <vector>

#include "bench_scene.h"
#include "phyir/render/rng.h"
#include "phyir/render/sampling.h"

namespace {

using namespace phyir;

std::vector<render::Ray> random_rays(size_t n) {
  const auto& s = bench::bench_scene();
  std::vector<render::Ray> rays(n);
  render::Rng rng(1, 2);
  for (auto& r : rays) {
    r.origin = s.viewpoint;
    r.direction = render::sample_uniform_sphere(rng.next_2d());
  }
  return rays;
}

void BM_IntersectSingle(benchmark::State& state) {
  const auto rays = random_rays(4096);
  const auto& accel = bench::bench_scene().render_scene->accelerator();
  for (auto _ : state) {
    for (const auto& r : rays) {
      render::Hit hit;
      benchmark::DoNotOptimize(accel.intersect(r, &hit));
    }
  }
  state.SetItemsProcessed(state.iterations() * rays.size());
}
BENCHMARK(BM_IntersectSingle);

void BM_IntersectPacket16(benchmark::State& state) {
  const auto rays = random_rays(4096);
  std::vector<float> t(rays.size());
  const auto& accel = bench::bench_scene().render_scene->accelerator();
  for (auto _ : state) {
    accel.intersect_batch(rays.data(), rays.size(), t.data());
    benchmark::DoNotOptimize(t.data());
  }
  state.SetItemsProcessed(state.iterations() * rays.size());
}
BENCHMARK(BM_IntersectPacket16);

void BM_Occluded(benchmark::State& state) {
  const auto rays = random_rays(4096);
  const auto& accel = bench::bench_scene().render_scene->accelerator();
  for (auto _ : state) {
    for (const auto& r : rays) benchmark::DoNotOptimize(accel.occluded(r));
  }
  state.SetItemsProcessed(state.iterations() * rays.size());
}
BENCHMARK(BM_Occluded);

void BM_TraceAndShade(benchmark::State& state) {
  const auto rays = random_rays(4096);
  const auto& scene = *bench::bench_scene().render_scene;
  for (auto _ : state) {
    for (const auto& r : rays) {
      render::SurfaceInteraction si;
      benchmark::DoNotOptimize(scene.trace(r, &si));
    }
  }
  state.SetItemsProcessed(state.iterations() * rays.size());
}
BENCHMARK(BM_TraceAndShade);

}  // namespace
