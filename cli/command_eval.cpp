// phyir eval: the paper's metrics and tables for any method's predictions (issue 7).
// docs/commands/eval.md, docs/eval.md
#include <cstdio>
#include <cstdlib>
#include <memory>

#include <tbb/global_control.h>

#include "commands.h"
#include "eval_insertion.h"
#include "phyir/core/error.h"
#include "phyir/core/progress.h"
#include "phyir/eval/report.h"
#include "phyir/eval/suite.h"

#ifdef PHYIR_HAVE_MODEL
#include "phyir/model/training.h"
#endif

namespace phyir::cli {
namespace {

struct EvalFlags {
  eval::EvalOptions options;
  std::string gt, pred, out, model;
  std::string depth_protocol = "toolkit";
  std::string radiance_units = "absolute";
  int threads = 0;
  int model_threads = 1;
  uint64_t model_seed = 1;
  bool no_relight = false, no_baselines = false, quiet = false;
  EvalInsertionOptions insertion;
};

// --model: `phyir infer` on each view's input.png into OUT/pred/<view id>/.
void run_model(const EvalFlags& f) {
#ifdef PHYIR_HAVE_MODEL
  const auto views = eval::split_views(f.gt, f.options.split);
  const size_t n = f.options.max_views > 0 ? std::min(views.size(), size_t(f.options.max_views)) : views.size();
  Progress progress("eval: inference", n, "views", !f.quiet);
  for (size_t k = 0; k < n; ++k) {
    model::InferOptions io;
    io.checkpoint = f.model;
    io.input = (views[k].dir / view::kInputFile).string();
    io.out_dir = (std::filesystem::path(f.out) / "pred" / views[k].id).string();
    io.threads = f.model_threads;
    io.seed = f.model_seed;
    model::infer(io);
    progress.advance();
  }
#else
  std::fprintf(stderr, "phyir eval --model: not available in this build (configured with -DPHYIR_BUILD_MODEL=OFF); "
                       "run phyir infer elsewhere and use --pred\n");
  std::exit(3);
#endif
}

// --insertion-*: the insertion section of the report (eval_insertion.h).
void add_insertion_flags(CLI::App* cmd, EvalInsertionOptions& o) {
  cmd->add_option("--insertion-views", o.views,
                  "also score object insertion (docs/insert.md) on the first N views of the split: Table 10's spheres "
                  "composited under the predicted probes, the GT probes, one global probe and a constant "
                  "environment, against the scene path traced with the sphere in it (0: off)")
      ->capture_default_str();
  cmd->add_option("--insertion-scenes", o.scenes,
                  "the dataset's scenes folder, where the manifest's scenes_dir is not reachable from here");
  cmd->add_option("--insertion-spp", o.spp, "samples per pixel of the insertion composites")
      ->capture_default_str();
  cmd->add_option("--insertion-truth-spp", o.truth_spp, "samples per pixel of the insertion truth")
      ->capture_default_str();
  cmd->add_option("--insertion-seeds", o.seeds, "seeds per insertion case (mean over them)")
      ->capture_default_str();
}

void run_eval_command(EvalFlags& f) {
  if (f.pred.empty() == f.model.empty()) fail("phyir eval: give exactly one of --pred DIR and --model CKPT");
  std::unique_ptr<tbb::global_control> limit;
  if (f.threads > 0)
    limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, f.threads);
  eval::EvalOptions& o = f.options;
  try {  // before any inference
    o.settings.depth_protocol = eval::parse_depth_protocol(f.depth_protocol);
  } catch (const Error& e) {
    fail("phyir eval --depth-protocol: {}", e.what());
  }
  try {
    o.settings.radiance_units = view::parse_radiance_units(f.radiance_units);
  } catch (const Error& e) {
    fail("phyir eval --radiance: {}", e.what());
  }
  o.gt_dir = f.gt;
  o.out_dir = f.out;
  o.settings.relight = !f.no_relight;
  o.baselines = !f.no_baselines;
  o.progress = !f.quiet;
  if (o.settings.sphere.size < 8 || o.settings.sphere.spp < 1 || o.settings.relight_positions < 0)
    fail("phyir eval: --sphere-size must be >= 8, --sphere-spp >= 1, --relight-positions >= 0");
  if (f.insertion.views < 0 || f.insertion.spp < 1 || f.insertion.truth_spp < 1 || f.insertion.seeds < 1)
    fail("phyir eval: --insertion-views must be >= 0, --insertion-spp, --insertion-truth-spp and "
         "--insertion-seeds >= 1");
  if (!f.model.empty()) {
    run_model(f);
    o.pred_dir = std::filesystem::path(f.out) / "pred";
    o.model = f.model;
  } else {
    o.pred_dir = f.pred;
  }
  if (f.insertion.views > 0) {
    EvalInsertionOptions& in = f.insertion;
    in.gt_dir = o.gt_dir, in.pred_dir = o.pred_dir, in.out_dir = o.out_dir, in.split = o.split;
    in.progress = o.progress;
    o.extra_sections.push_back(evaluate_insertion(in));
  }
  const nlohmann::json metrics = eval::run_eval(o);
  std::printf("%s\nwrote %s/report.md and %s/metrics.json\n", eval::main_table_markdown(metrics).c_str(),
              f.out.c_str(), f.out.c_str());
}

}  // namespace

void add_eval_command(CLI::App& app) {
  auto f = std::make_shared<EvalFlags>();
  auto* cmd = app.add_subcommand(
      "eval", "Compute the paper's metrics and tables (materials, normals, depth, probe SSIM, relighting) "
              "for a method's predictions on a dataset split; writes report.md, metrics.json and figures");
  cmd->add_option("--gt", f->gt, "ground truth: a dataset folder of phyir dataset (manifest.json)")
      ->required()->check(CLI::ExistingDirectory);
  cmd->add_option("--split", f->options.split, "the manifest's split to evaluate (\"\" = every view)")
      ->capture_default_str();
  auto* pred = cmd->add_option("--pred", f->pred,
                               "predictions: PRED/<view id>/ holding depth.exr, normal.exr, basecolor.exr, roughness.exr, "
                               "metalness.exr [, rerender.exr, probes.exr + probe_mask.exr] as phyir infer writes them");
  auto* model = cmd->add_option("--model", f->model, "instead of --pred: run this checkpoint (phyir infer) on each "
                                                     "view's input.png into OUT/pred/ first")
                    ->check(CLI::ExistingFile);
  pred->excludes(model);
  cmd->add_option("--out", f->out, "report folder: report.md, metrics.json, figures/ (and pred/ with --model)")
      ->required();
  cmd->add_option("--relight-positions", f->options.settings.relight_positions,
                  "probe positions relit per view (spread over the valid probes)")->capture_default_str();
  cmd->add_option("--sphere-size", f->options.settings.sphere.size, "relit sphere image size in pixels")
      ->capture_default_str();
  cmd->add_option("--sphere-spp", f->options.settings.sphere.spp, "samples per pixel of the relit spheres")
      ->capture_default_str();
  cmd->add_option("--seed", f->options.settings.sphere.seed, "seed of the relighting renders")->capture_default_str();
  cmd->add_option("--depth-protocol", f->depth_protocol,
                  "rules of the depth metrics: toolkit (the maps' mask, RMSE log in ln), unifuse (UniFuse's "
                  "evaluation exactly: ground truth in (0, 10] m, its clamps at 0.1 and 10 m, RMSE log in log10), "
                  "unifuse-median (the same with its median alignment); docs/eval.md")->capture_default_str();
  cmd->add_option("--radiance", f->radiance_units,
                  "unit of the radiance metrics (re-render, probes, relighting): absolute (color.exr's) or input "
                  "(both sides times the view's 2^exposure_stops, the network's training unit); docs/eval.md")
      ->capture_default_str();
  cmd->add_flag("--no-relight", f->no_relight, "skip the relighting spheres (Table 5)");
  cmd->add_flag("--no-baselines", f->no_baselines, "skip the baseline rows");
  cmd->add_option("--baseline-max-views", f->options.baseline_max_views,
                  "training views the constant-mean baseline averages (first N; 0 = all)")->capture_default_str();
  cmd->add_option("--figures", f->options.figures, "side-by-side PNGs for the first N views")->capture_default_str();
  cmd->add_option("--max-views", f->options.max_views, "evaluate only the first N views of the split (0 = all)")
      ->capture_default_str();
  cmd->add_option("--threads", f->threads, "renderer threads for the relighting (0 = all cores)")->capture_default_str();
  cmd->add_option("--model-threads", f->model_threads, "torch threads for --model")->capture_default_str();
  cmd->add_option("--model-seed", f->model_seed, "seed of the rendering layer's samples for --model")
      ->capture_default_str();
  add_insertion_flags(cmd, f->insertion);
  cmd->add_flag("--quiet", f->quiet, "no progress line");
  cmd->callback([f] { run_eval_command(*f); });
}

}  // namespace phyir::cli
