// Cost of the UE4 BRDF's eval, pdf and sample (appendix A.3), per call.
#include <benchmark/benchmark.h>

#include <vector>

#include "phyir/render/brdf.h"
#include "phyir/render/rng.h"
#include "phyir/render/sampling.h"

namespace {

using namespace phyir::render;

struct Inputs {
  std::vector<BrdfParams> params;
  std::vector<glm::vec3> wo, wi;
  std::vector<glm::vec2> u;
};

Inputs make_inputs(size_t n) {
  Inputs in;
  Rng rng(3, 4);
  for (size_t i = 0; i < n; ++i) {
    in.params.push_back({glm::vec3(rng.next_float(), rng.next_float(), rng.next_float()), rng.next_float(), rng.next_float()});
    in.wo.push_back(sample_cosine_hemisphere(rng.next_2d()));
    in.wi.push_back(sample_cosine_hemisphere(rng.next_2d()));
    in.u.push_back(rng.next_2d());
  }
  return in;
}

void BM_BrdfEval(benchmark::State& state) {
  const Inputs in = make_inputs(1024);
  for (auto _ : state)
    for (size_t i = 0; i < in.wo.size(); ++i) benchmark::DoNotOptimize(brdf_eval(in.params[i], in.wo[i], in.wi[i]));
  state.SetItemsProcessed(state.iterations() * in.wo.size());
}
BENCHMARK(BM_BrdfEval);

void BM_BrdfPdf(benchmark::State& state) {
  const Inputs in = make_inputs(1024);
  for (auto _ : state)
    for (size_t i = 0; i < in.wo.size(); ++i) benchmark::DoNotOptimize(brdf_pdf(in.params[i], in.wo[i], in.wi[i]));
  state.SetItemsProcessed(state.iterations() * in.wo.size());
}
BENCHMARK(BM_BrdfPdf);

void BM_BrdfSample(benchmark::State& state) {
  const Inputs in = make_inputs(1024);
  for (auto _ : state)
    for (size_t i = 0; i < in.wo.size(); ++i) {
      BrdfSample s;
      benchmark::DoNotOptimize(brdf_sample(in.params[i], in.wo[i], in.u[i].x, in.u[i], &s));
    }
  state.SetItemsProcessed(state.iterations() * in.wo.size());
}
BENCHMARK(BM_BrdfSample);

}  // namespace
