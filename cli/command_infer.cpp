// phyir infer: run a trained PhyIR network on a panorama. docs/commands/infer.md
#include <cstdio>
#include <cstdlib>
#include <memory>

#include "commands.h"
#include "flag_registry.h"
#include "torch_handoff.h"
#include "phyir/core/error.h"

#ifdef PHYIR_HAVE_MODEL
#include "phyir/model/training.h"
#endif

namespace phyir::cli {

#ifdef PHYIR_HAVE_MODEL

void add_infer_command(CLI::App& app) {
  auto o = std::make_shared<model::InferOptions>();
  auto* cmd = app.add_subcommand(
      "infer", "Run a trained network on a panorama: depth, normal, base colour, roughness, metalness, "
               "probes and the re-rendered image, in the renderer's conventions");
  cmd->add_option("--model", o->checkpoint, "checkpoint.pt written by phyir train")->check(CLI::ExistingFile);
  cmd->add_option("--input", o->input, "equirect panorama: .png (LDR, as input.png) or .exr/.hdr (HDR: exposed, then sRGB-encoded)")
      ->check(CLI::ExistingFile);
  cmd->add_option("--out", o->out_dir, "output folder")->required();
  cmd->add_option("--threads", o->threads, "torch threads (0: every core; the outputs are the same for any count)")
      ->capture_default_str();
  sets(cmd, "device",
       cmd->add_option("--device", o->device, "cpu, cuda or cuda:N (CUDA needs a CUDA LibTorch: docs/model-scale.md \"Build\")"))
      ->capture_default_str();
  cmd->add_option("--seed", o->seed, "seed of the rendering layer's samples")->capture_default_str();
  cmd->add_option("--exposure", o->exposure,
                  "the input's exposure in stops: an .exr is exposed by it (default: the dataset's auto exposure); "
                  "a .png was written at it (default: its folder's view.json, else unknown)");
  auto radiance = std::make_shared<std::string>("absolute");
  cmd->add_option("--radiance", *radiance,
                  "unit of probes.exr and rerender.exr: absolute (when the exposure is known) or input (the "
                  "input's relative units, as the network predicts them)")
      ->check(CLI::IsMember({"absolute", "input"}))
      ->capture_default_str();
  auto check = std::make_shared<model::RenderCheckOptions>();
  cmd->add_option("--check-render-layer", check->view_dir,
                  "instead: re-render a view folder's ground-truth maps and probes (phyir render --probes) "
                  "with the rendering layer and report the MSE against its color.exr")
      ->check(CLI::ExistingDirectory);
  cmd->add_option("--diffuse-samples", check->diffuse_samples, "with --check-render-layer")->capture_default_str();
  cmd->add_option("--specular-samples", check->specular_samples, "with --check-render-layer")->capture_default_str();
  cmd->callback([o, check, radiance] {
    o->absolute = *radiance == "absolute";
    if (!check->view_dir.empty()) {
      check->out_dir = o->out_dir;
      check->seed = o->seed;
      check->threads = o->threads;
      const model::RenderCheckResult r = model::check_render_layer(*check);
      std::printf("rendering layer on ground truth: %dx%d, %lld pixels, MSE %.6g, relative MSE %.4g, "
                  "mean colour %.5g, mean re-render %.5g, mean abs error %.5g\n",
                  r.width, r.height, static_cast<long long>(r.pixels), r.mse, r.relative_mse, r.mean_color,
                  r.mean_rerender, r.mean_abs_error);
      return;
    }
    if (o->checkpoint.empty() || o->input.empty()) fail("phyir infer: --model and --input are required (or --check-render-layer VIEW)");
    model::infer(*o);
  });
}

#else

// `phyir` lists the command in --help. With the network built, main() hands the command to
// phyir-torch before parsing (torch_handoff.h); without it, the callback says it was not built.
void add_infer_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("infer", "Run a trained network" + torch_build_note());
  // Every argument after the command is the network command's: kept here, not passed up to
  // phyir (main() sets fallthrough, which would refuse them there).
  cmd->fallthrough(false)->prefix_command();
  cmd->callback([] { run_in_torch_cli("infer"); });
}

#endif

}  // namespace phyir::cli
