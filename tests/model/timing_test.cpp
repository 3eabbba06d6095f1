// Module timings (issue 6, item 8), disabled by default (slow): run with
//   model_test --gtest_also_run_disabled_tests --gtest_filter='ModelTiming.*'
// PHYIR_TIMING_THREADS sets the thread count (default 2); PHYIR_TIMING_PAPER=1 adds the paper's
// resolution (256x512 input, 128x256 rendering, 16x32 probes, 512/256 samples).
#include <chrono>
#include <cstdlib>

#include "nets.h"
#include "render_layer.h"

namespace pm = phyir::model;

namespace {

template <typename Fn>
double best_ms(Fn&& fn, int reps = 3) {
  fn();  // warm-up: oneDNN builds its primitives on the first call of each shape
  double best = 1e30;
  for (int i = 0; i < reps; ++i) {
    const auto t0 = std::chrono::steady_clock::now();
    fn();
    best = std::min(best, std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
  }
  return best;
}

int threads() {
  const char* t = std::getenv("PHYIR_TIMING_THREADS");
  return t ? std::atoi(t) : 2;
}

}  // namespace

TEST(ModelTiming, DISABLED_ModulesAtDefaultAndPaperResolution) {
  torch::set_num_threads(threads());
  torch::manual_seed(1);
  struct Res {
    const char* name;
    int Hi, Wi, Hr, Wr, h, w, nd, ns;
  };
  std::vector<Res> runs = {Res{"default", 128, 256, 32, 64, 8, 16, 64, 32}};
  // The paper's resolution needs several GiB for the rendering layer's backward pass.
  if (std::getenv("PHYIR_TIMING_PAPER")) runs.push_back(Res{"paper", 256, 512, 128, 256, 16, 32, 512, 256});
  for (const Res& r : runs) {
    pm::GMNet gm;
    pm::LNet ln(r.h, r.w);
    pm::GSNet gs(2);
    gm->eval();
    ln->eval();
    gs->eval();
    const auto image = torch::rand({1, 3, r.Hi, r.Wi});
    pm::GMOutput o;
    double t_gm, t_ln, t_gs, t_rl, t_rl_fb;
    {
      torch::NoGradGuard ng;
      t_gm = best_ms([&] { o = gm->forward(image); });
      t_gs = best_ms([&] { gs->forward(image, o); });
      const auto in = pm::lnet_input(image, o, r.Hr, r.Wr);
      torch::Tensor lp;
      t_ln = best_ms([&] { lp = ln->forward(in); });
      pm::RenderSettings rs;
      rs.diffuse_samples = r.nd;
      rs.specular_samples = r.ns;
      const auto n = torch::nn::functional::normalize(torch::rand({1, 3, r.Hr, r.Wr}) - 0.5,
                                                      torch::nn::functional::NormalizeFuncOptions().dim(1));
      const auto probes = torch::expm1(lp);
      t_rl = best_ms([&] {
        pm::render_layer(n, torch::rand({1, 3, r.Hr, r.Wr}), torch::rand({1, 1, r.Hr, r.Wr}),
                         torch::rand({1, 1, r.Hr, r.Wr}), probes, rs);
      }, 1);
    }
    {
      pm::RenderSettings rs;
      rs.diffuse_samples = r.nd;
      rs.specular_samples = r.ns;
      auto n = torch::nn::functional::normalize(torch::rand({1, 3, r.Hr, r.Wr}) - 0.5,
                                                torch::nn::functional::NormalizeFuncOptions().dim(1))
                   .set_requires_grad(true);
      auto probes = torch::rand({1, r.Hr, r.Wr, r.h, r.w, 3}).set_requires_grad(true);
      auto rough = torch::rand({1, 1, r.Hr, r.Wr}).set_requires_grad(true);
      t_rl_fb = best_ms([&] {
        pm::render_layer(n, torch::rand({1, 3, r.Hr, r.Wr}), rough, torch::rand({1, 1, r.Hr, r.Wr}), probes, rs)
            .image.sum()
            .backward();
      }, 1);
    }
    std::printf("[ModelTiming] %s (%d threads): input %dx%d, render %dx%d, probes %dx%d, samples %d/%d\n"
                "  GMNet %.0f ms, GSNet %.0f ms, LNet %.0f ms, rendering layer %.0f ms (forward+backward %.0f ms),"
                " full inference %.0f ms\n",
                r.name, threads(), r.Wi, r.Hi, r.Wr, r.Hr, r.w, r.h, r.nd, r.ns, t_gm, t_gs, t_ln, t_rl, t_rl_fb,
                t_gm + t_gs + t_ln + t_rl);
  }
}
