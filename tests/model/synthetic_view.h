#pragma once
// A synthetic view folder as the dataset writes it (training, streaming and device tests).
#include <torch/torch.h>

#include <filesystem>

#include "data.h"
#include "nets.h"
#include "render_layer.h"

namespace synthetic {

namespace pm = phyir::model;

// A view folder as the dataset writes it, 64 x 32, probes on a 32 x 16 grid of 4 x 8 texels.
inline void write_view(const std::filesystem::path& dir, int seed) {
  namespace fs = std::filesystem;
  fs::create_directories(dir);
  const int H = 32, W = 64, gh = 16, gw = 32, h = 4, w = 8;
  torch::manual_seed(seed);
  const auto dirs = pm::pixel_directions(H, W, torch::TensorOptions());  // [H,W,3]
  const auto d = dirs.permute({2, 0, 1});
  const auto depth = (2.0 + 0.5 * d[1] + 0.2 * seed).unsqueeze(0);
  const auto normal = -d;
  const auto base = torch::stack({0.5 + 0.3 * d[0], 0.4 + 0.1 * torch::rand({H, W}), torch::full({H, W}, 0.3 + 0.1 * seed)});
  const auto rough = (0.3 + 0.4 * (d[1] > 0).to(torch::kFloat)).unsqueeze(0);
  const auto metal = (d[0] > 0.5).to(torch::kFloat).unsqueeze(0);
  const auto color = base * (1.2 + 0.5 * d[1]);
  const auto tdirs = pm::pixel_directions(h, w, torch::TensorOptions());
  const auto probe = (1.0 + 0.5 * tdirs.select(-1, 1) + 0.1 * seed).view({1, 1, 1, h, w, 1}).expand({1, gh, gw, h, w, 3});
  pm::write_tensor_image(dir / "color.exr", color);
  pm::write_tensor_image(dir / "input.png", color.clamp(0.0, 1.0).pow(1.0 / 2.2));
  pm::write_tensor_image(dir / "depth.exr", depth, {"Y"});
  pm::write_tensor_image(dir / "normal.exr", normal, {"X", "Y", "Z"});
  pm::write_tensor_image(dir / "basecolor.exr", base);
  pm::write_tensor_image(dir / "roughness.exr", rough, {"Y"});
  pm::write_tensor_image(dir / "metalness.exr", metal, {"Y"});
  pm::write_tensor_image(dir / "mask_geometry.exr", torch::ones({1, H, W}), {"Y"});
  pm::write_tensor_image(dir / "mask_emissive.exr", torch::zeros({1, H, W}), {"Y"});
  pm::write_tensor_image(dir / "mask_transparent.exr", torch::zeros({1, H, W}), {"Y"});
  pm::write_tensor_image(dir / "probes.exr", pm::probes_to_mosaic(probe.contiguous())[0]);
  pm::write_tensor_image(dir / "probe_mask.exr", torch::ones({1, gh, gw}), {"Y"});
}

}  // namespace synthetic
