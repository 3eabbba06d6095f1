#pragma once
// The physics-based in-network rendering layer (paper eqs. 9-10, 13-18) and the probe warp
// (eq. 8). The BRDF terms give the same numbers as render/brdf.h (tests/model checks it).
// Private header (torch types).
#include <torch/torch.h>

#include "safe_math.h"  // kMinCosine, safe_acos, ... (the torch mirror of core/safe_math.h)

namespace phyir::model {

// Same constant as render/brdf.h (kept equal by a test), stored as the float value, so float
// tensors compare exactly as the renderer does.
constexpr double kMirrorRoughness = static_cast<double>(0.008f);
// Below this x^2 + z^2 a direction is on the Y axis for the equirect mapping: atan2's gradient
// (-z, x) / (x^2 + z^2) would be 0/0 there, so u is taken as the centre column.
constexpr double kAtan2MinRadius2 = 1e-12;
// The rendering layer normalises its normal input by sqrt(max(|n|^2, this)).
constexpr double kNormalMinLength2 = 1e-12;

// --- BRDF terms (appendix A.3), elementwise on broadcastable tensors --------------------------
torch::Tensor D_GGX(const torch::Tensor& NoH, const torch::Tensor& alpha);     // eq. 15
torch::Tensor F_SchlickSG(const torch::Tensor& F0, const torch::Tensor& VoH);  // eq. 16
torch::Tensor specular_F0(const torch::Tensor& base_color, const torch::Tensor& metalness);
torch::Tensor G1_SmithSchlick(const torch::Tensor& NoX, const torch::Tensor& k);  // eq. 17
torch::Tensor G_SmithSchlick(const torch::Tensor& NoV, const torch::Tensor& NoL,
                             const torch::Tensor& roughness);  // eq. 17
torch::Tensor Fd_Lambert(const torch::Tensor& base_color, const torch::Tensor& metalness);  // eq. 13

// f_r(wo, wi) in the local frame (n = +z) without the cosine, as render::brdf_eval:
// base_color [...,3], roughness/metalness [...,1], wo/wi [...,3]. Returns [...,3]; zero when
// either direction is below kMinCosine; the mirror lobe (R < kMirrorRoughness) is excluded.
torch::Tensor brdf_eval(const torch::Tensor& base_color, const torch::Tensor& roughness,
                        const torch::Tensor& metalness, const torch::Tensor& wo,
                        const torch::Tensor& wi);

// --- Equirect mapping (docs/conventions.md) -------------------------------------------------
// Unit direction [...,3] -> (u, v) [...,2]; safe (finite gradients) at the poles.
torch::Tensor equirect_uv(const torch::Tensor& dir);
// (u, v) [...,2] -> unit direction [...,3].
torch::Tensor equirect_direction(const torch::Tensor& uv);
// Directions of the pixel centres of an H x W panorama: [H, W, 3].
torch::Tensor pixel_directions(int height, int width, const torch::TensorOptions& opts);

// Bilinear lookup (wrap in u, clamp in v) of per-pixel probes.
//   probes [P, h, w, 3] (linear or log radiance), dirs [P, S, 3] world directions
//   returns [P, S, 3].
torch::Tensor sample_probes(const torch::Tensor& probes, const torch::Tensor& dirs);

// --- Rendering layer ------------------------------------------------------------------------
struct RenderSettings {
  int diffuse_samples = 64;   // paper: 512
  int specular_samples = 32;  // paper: 256
  int64_t max_pixels_per_chunk = 4096;  // unused since the fused kernel (kept for callers)
  int64_t first_stream = 0;   // the random stream of the batch's first pixel (a rank's share of a
                              // batch continues the global batch's numbering: batch_share.h)
};

struct RenderOutput {
  torch::Tensor image;     // [B,3,H,W] = diffuse + specular
  torch::Tensor diffuse;   // [B,3,H,W]
  torch::Tensor specular;  // [B,3,H,W]
};

// Renders each pixel of an equirect panorama seen from the origin: view direction
// v = -d(pixel), the surface BRDF from the maps, incident light from the pixel's probe
// (linear radiance [B,H,W,h,w,3]). Importance sampling per eq. 18: cosine for the diffuse
// lobe (its estimator reduces to B(1-M) mean L), GGX half vectors for the specular lobe (its
// estimator F G VoH / (NoV NoH) has D cancelled, so nothing divides by alpha); for
// R < kMirrorRoughness the specular lobe is the delta reflection with F(NoV) G1(NoV)^2.
// Random numbers: one seed drawn from torch's default generator (seed it for determinism),
// then pixel p's own stream (render_kernel.h), so the thread count does not change the result.
// On the CPU it runs the fused kernel (render_kernel.cpp): memory O(pixels) in forward and
// backward. On another device (a cuda device) render_layer_reference's estimator on the same
// uniforms (the kernel is CPU code).
RenderOutput render_layer(const torch::Tensor& normal, const torch::Tensor& base_color,
                          const torch::Tensor& roughness, const torch::Tensor& metalness,
                          const torch::Tensor& probes, const RenderSettings& settings);

// The same estimator composed of torch operations (autograd through every intermediate; O(pixels
// x samples) memory), from given uniforms (render_uniforms in render_kernel.h): the
// specification the fused kernel is tested against.
RenderOutput render_layer_reference(const torch::Tensor& normal, const torch::Tensor& base_color,
                                    const torch::Tensor& roughness, const torch::Tensor& metalness,
                                    const torch::Tensor& probes, const torch::Tensor& diffuse_uniforms,
                                    const torch::Tensor& specular_uniforms);

// --- Probe warp (eq. 8) ---------------------------------------------------------------------
// Re-projects the probe of pixel q (neighbour) to the 3D position of pixel p. Every probe
// texel direction w of p is a ray X_p + t w; the scene seen from q is approximated by a
// sphere of radius rho centred at X_q (rho = the view's mean depth, detached, at least
// 2 |X_p - X_q|); the ray's exit point P gives the direction w' = (P - X_q)/|P - X_q| at
// which q's probe is sampled (bilinear). X = depth * d(pixel). Parallel and differentiable
// in probes and depth.
//   probes_q [B,H,W,h,w,3], depth_p/depth_q [B,1,H,W] (same pixel grid as probes; q's
//   depth and probes already shifted onto p's grid), dir_p/dir_q [H,W,3].
torch::Tensor warp_probes(const torch::Tensor& probes_q, const torch::Tensor& depth_p,
                          const torch::Tensor& depth_q, const torch::Tensor& dir_p,
                          const torch::Tensor& dir_q);

}  // namespace phyir::model
