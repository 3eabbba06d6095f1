#pragma once
// The rendering layer's fused CPU kernel (eqs. 9-10, 13-18): one loop per pixel over its
// samples, probe lookup fused with the direction-to-texel arithmetic, no [pixels, samples, ...]
// intermediate. Backward recomputes the samples from the inputs and the seed (a custom autograd
// Function that stores only its inputs), so memory is O(pixels), not O(pixels x samples).
// It computes exactly what render_layer_reference (render_layer.h) computes from the same
// uniforms: tests/model compares values and gradients. Private header (torch types).
#include <torch/torch.h>

#include <cstdint>

namespace phyir::model {

struct FusedRenderOutput {
  torch::Tensor diffuse;   // [P,3]
  torch::Tensor specular;  // [P,3]
};

// n [P,3] (normalised inside), v [P,3] unit view directions (no gradient), base colour [P,3],
// roughness and metalness [P,1], probes [P,h,w,3] linear radiance; float or double.
// Pixel p draws its uniforms from Pcg32(mix64(seed), first_stream + p): the result does not
// depend on the thread count, and a rank's share of a batch continues the whole batch's streams. Differentiable in n, base colour, roughness, metalness and probes.
FusedRenderOutput render_pixels_fused(const torch::Tensor& n, const torch::Tensor& v,
                                      const torch::Tensor& base_color, const torch::Tensor& roughness,
                                      const torch::Tensor& metalness, const torch::Tensor& probes,
                                      int diffuse_samples, int specular_samples, uint64_t seed,
                                      uint64_t first_stream = 0);

// The uniforms the kernel draws for P pixels (clamped as it clamps them): diffuse [P,Nd,2] in
// [0, 1 - 1e-7], specular [P,Ns,2] in [1e-6, 1 - 1e-6]. For render_layer_reference in tests.
std::pair<torch::Tensor, torch::Tensor> render_uniforms(int64_t pixels, int diffuse_samples, int specular_samples,
                                                        uint64_t seed, torch::Dtype dtype,
                                                        uint64_t first_stream = 0);

}  // namespace phyir::model
