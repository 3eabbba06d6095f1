// Rendering layer (eqs. 9-10, 13-18) and probe warp (eq. 8).
#include "render_layer.h"

#include <algorithm>
#include <limits>

#include "render_kernel.h"

namespace phyir::model {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kMinAlpha = kMirrorRoughness * kMirrorRoughness;

// Eq. 15 from cos^2 and sin^2 of theta_h, exactly as render/brdf.cpp's ggx_ndf.
torch::Tensor ggx_ndf(const torch::Tensor& cos2, const torch::Tensor& sin2, const torch::Tensor& alpha) {
  const torch::Tensor a = alpha.clamp_min(kMinAlpha);
  const torch::Tensor a2 = a * a;
  const torch::Tensor d = cos2 * a2 + sin2;
  return a2 / (static_cast<float>(kPi) * d * d);
}

torch::Tensor schlick_k(const torch::Tensor& roughness) {
  const torch::Tensor r1 = roughness + 1.0;
  return r1 * r1 / 8.0;
}

torch::Tensor comp(const torch::Tensor& v, int64_t i) { return v.select(-1, i).unsqueeze(-1); }

torch::Tensor dot3(const torch::Tensor& a, const torch::Tensor& b) {
  return (a * b).sum(-1, true);
}

}  // namespace

// --- BRDF terms -------------------------------------------------------------------------------

torch::Tensor D_GGX(const torch::Tensor& NoH_in, const torch::Tensor& alpha) {
  const torch::Tensor NoH = NoH_in.clamp(0.0, 1.0);
  const torch::Tensor D = ggx_ndf(NoH * NoH, (1.0 - NoH) * (1.0 + NoH), alpha);
  return torch::where(NoH_in > 0.0, D, torch::zeros_like(D));
}

torch::Tensor F_SchlickSG(const torch::Tensor& F0, const torch::Tensor& VoH_in) {
  const torch::Tensor VoH = VoH_in.clamp(0.0, 1.0);
  const torch::Tensor fc = torch::exp2((-5.55473 * VoH - 6.98316) * VoH);
  return F0 + (1.0 - F0) * fc;
}

torch::Tensor specular_F0(const torch::Tensor& base_color, const torch::Tensor& metalness) {
  return 0.04 * (1.0 - metalness) + metalness * base_color;
}

torch::Tensor G1_SmithSchlick(const torch::Tensor& NoX_in, const torch::Tensor& k) {
  const torch::Tensor NoX = NoX_in.clamp(0.0, 1.0);
  return NoX / (NoX * (1.0 - k) + k);
}

torch::Tensor G_SmithSchlick(const torch::Tensor& NoV, const torch::Tensor& NoL,
                             const torch::Tensor& roughness) {
  const torch::Tensor k = schlick_k(roughness.clamp(0.0, 1.0));
  return G1_SmithSchlick(NoV, k) * G1_SmithSchlick(NoL, k);
}

torch::Tensor Fd_Lambert(const torch::Tensor& base_color, const torch::Tensor& metalness) {
  return base_color * (1.0 - metalness) * static_cast<float>(1.0 / kPi);
}

torch::Tensor brdf_eval(const torch::Tensor& base_color_in, const torch::Tensor& roughness_in,
                        const torch::Tensor& metalness_in, const torch::Tensor& wo,
                        const torch::Tensor& wi) {
  const torch::Tensor B = base_color_in.clamp(0.0, 1.0);
  const torch::Tensor R = roughness_in.clamp(0.0, 1.0);
  const torch::Tensor M = metalness_in.clamp(0.0, 1.0);
  const torch::Tensor NoV = comp(wo, 2), NoL = comp(wi, 2);
  const torch::Tensor valid = (NoV >= kMinCosine) & (NoL >= kMinCosine);
  const torch::Tensor s = wo + wi;
  // wi = -wo (s = 0) has no half vector: there (always an invalid pair, zeroed below) take
  // h = n. Replacing the denominator before dividing keeps the unused branch finite, so the
  // final torch::where sends back 0, not 0 * inf = NaN (as safe_div in safe_math.h).
  const torch::Tensor len2_raw = dot3(s, s);
  const torch::Tensor has_h = len2_raw > kTinyDenominator;
  const torch::Tensor len2 = torch::where(has_h, len2_raw, torch::ones_like(len2_raw));
  const torch::Tensor sz = comp(s, 2);
  const torch::Tensor cos2 = torch::where(has_h, sz * sz / len2, torch::ones_like(len2));
  const torch::Tensor sin2 =
      torch::where(has_h, (comp(s, 0) * comp(s, 0) + comp(s, 1) * comp(s, 1)) / len2, torch::zeros_like(len2));
  const torch::Tensor VoH = torch::where(has_h, (0.5 * torch::sqrt(len2)).clamp_max(1.0), torch::zeros_like(len2));
  const torch::Tensor D = ggx_ndf(cos2, sin2, R * R);
  const torch::Tensor F = F_SchlickSG(specular_F0(B, M), VoH);
  const torch::Tensor G = G_SmithSchlick(NoV, NoL, R);
  const torch::Tensor NoVc = NoV.clamp_min(kMinCosine), NoLc = NoL.clamp_min(kMinCosine);
  const torch::Tensor fs = D * F * G / (4.0 * (NoVc * NoLc));
  const torch::Tensor mirror = R < kMirrorRoughness;
  const torch::Tensor f = Fd_Lambert(B, M) + torch::where(mirror, torch::zeros_like(fs), fs);
  return torch::where(valid, f, torch::zeros_like(f));
}

// --- Equirect mapping ---------------------------------------------------------------------

torch::Tensor equirect_uv(const torch::Tensor& dir) {
  const torch::Tensor x = comp(dir, 0), y = comp(dir, 1), z = comp(dir, 2);
  // atan2's gradient is 0/0 on the Y axis: there u is arbitrary, take the centre column.
  const torch::Tensor safe = (x * x + z * z) > kAtan2MinRadius2;
  const torch::Tensor xs = torch::where(safe, x, torch::zeros_like(x));
  const torch::Tensor zs = torch::where(safe, z, -torch::ones_like(z));
  const torch::Tensor u = 0.5 + torch::atan2(xs, -zs) * (0.5 / kPi);
  const torch::Tensor v = safe_acos(y) * (1.0 / kPi);  // finite gradient at the poles
  return torch::cat({u, v}, -1);
}

torch::Tensor equirect_direction(const torch::Tensor& uv) {
  const torch::Tensor phi = (comp(uv, 0) - 0.5) * (2.0 * kPi);
  const torch::Tensor theta = comp(uv, 1) * kPi;
  const torch::Tensor st = torch::sin(theta);
  return torch::cat({st * torch::sin(phi), torch::cos(theta), -st * torch::cos(phi)}, -1);
}

torch::Tensor pixel_directions(int height, int width, const torch::TensorOptions& opts) {
  const torch::Tensor u = (torch::arange(width, opts) + 0.5) / width;
  const torch::Tensor v = (torch::arange(height, opts) + 0.5) / height;
  const torch::Tensor uv = torch::stack({u.view({1, width}).expand({height, width}),
                                         v.view({height, 1}).expand({height, width})},
                                        -1);
  return equirect_direction(uv);
}

torch::Tensor sample_probes(const torch::Tensor& probes, const torch::Tensor& dirs) {
  const int64_t P = probes.size(0), h = probes.size(1), w = probes.size(2), S = dirs.size(1);
  const torch::Tensor uv = equirect_uv(dirs);
  const torch::Tensor x = comp(uv, 0) * static_cast<double>(w) - 0.5;  // texel centres at i + 0.5
  const torch::Tensor y = comp(uv, 1) * static_cast<double>(h) - 0.5;
  const torch::Tensor x0 = torch::floor(x).detach(), y0 = torch::floor(y).detach();
  const torch::Tensor fx = x - x0, fy = y - y0;
  const torch::Tensor ix0 = torch::remainder(x0, static_cast<double>(w)).to(torch::kLong);
  const torch::Tensor ix1 = torch::remainder(x0 + 1.0, static_cast<double>(w)).to(torch::kLong);
  const torch::Tensor iy0 = y0.clamp(0.0, static_cast<double>(h - 1)).to(torch::kLong);
  const torch::Tensor iy1 = (y0 + 1.0).clamp(0.0, static_cast<double>(h - 1)).to(torch::kLong);
  const torch::Tensor idx = torch::cat({iy0 * w + ix0, iy0 * w + ix1, iy1 * w + ix0, iy1 * w + ix1}, 1);
  const torch::Tensor flat = probes.reshape({P, h * w, 3});
  const torch::Tensor g = torch::gather(flat, 1, idx.expand({P, 4 * S, 3}));
  const torch::Tensor c00 = g.narrow(1, 0, S), c01 = g.narrow(1, S, S), c10 = g.narrow(1, 2 * S, S),
                      c11 = g.narrow(1, 3 * S, S);
  return (c00 * (1.0 - fx) + c01 * fx) * (1.0 - fy) + (c10 * (1.0 - fx) + c11 * fx) * fy;
}

// --- Rendering layer --------------------------------------------------------------------------

namespace {

// Renders P pixels: n, v [P,3]; B [P,3]; R, M [P,1]; probes [P,h,w,3]; uniforms ud [P,Nd,2],
// us [P,Ns,2] (clamped as render_uniforms clamps them). Returns {diffuse, specular}.
std::pair<torch::Tensor, torch::Tensor> render_pixels(const torch::Tensor& n_in, const torch::Tensor& v,
                                                      const torch::Tensor& B_in, const torch::Tensor& R_in,
                                                      const torch::Tensor& M_in, const torch::Tensor& probes,
                                                      const torch::Tensor& ud, const torch::Tensor& us) {
  const int64_t P = n_in.size(0);
  const auto opts = n_in.options();
  const torch::Tensor B = B_in.clamp(0.0, 1.0), R = R_in.clamp(0.0, 1.0), M = M_in.clamp(0.0, 1.0);
  const torch::Tensor n = n_in / torch::sqrt(dot3(n_in, n_in).clamp_min(kNormalMinLength2));
  // Orthonormal basis around n (Duff et al. 2017): |sign + n.z| >= 1, so no division by ~0.
  const torch::Tensor nx = comp(n, 0), ny = comp(n, 1), nz = comp(n, 2);
  const torch::Tensor sign = torch::where(nz >= 0.0, torch::ones_like(nz), -torch::ones_like(nz));
  const torch::Tensor a = -1.0 / (sign + nz);
  const torch::Tensor b = nx * ny * a;
  const torch::Tensor t = torch::cat({1.0 + sign * nx * nx * a, sign * b, -sign * nx}, -1);
  const torch::Tensor bt = torch::cat({b, sign + ny * ny * a, -ny}, -1);
  auto to_world = [&](const torch::Tensor& l) {  // l [P,S,3] local -> world
    return comp(l, 0) * t.unsqueeze(1) + comp(l, 1) * bt.unsqueeze(1) + comp(l, 2) * n.unsqueeze(1);
  };
  const torch::Tensor vl = torch::cat({dot3(v, t), dot3(v, bt), dot3(v, n)}, -1);  // [P,3]
  const torch::Tensor NoV_raw = comp(vl, 2);
  // As render::brdf_eval: a surface seen from below (or within kMinCosine of grazing) is black.
  const torch::Tensor valid_v = (NoV_raw >= kMinCosine).to(opts.dtype());
  const torch::Tensor NoV = NoV_raw.clamp(kMinCosine, 1.0);

  // Diffuse lobe, cosine-weighted samples (eq. 18): f_d L cos / (cos/pi) = B (1 - M) L.
  torch::Tensor diffuse = torch::zeros({P, 3}, opts);
  if (ud.size(1) > 0) {
    const torch::Tensor& u = ud;
    const torch::Tensor u1 = comp(u, 0), phi = comp(u, 1) * static_cast<float>(2.0 * kPi);
    const torch::Tensor r = torch::sqrt(u1), z = torch::sqrt(1.0 - u1);
    const torch::Tensor l = torch::cat({r * torch::cos(phi), r * torch::sin(phi), z}, -1);
    const torch::Tensor L = sample_probes(probes, to_world(l)) * (z >= kMinCosine).to(opts.dtype());
    diffuse = Fd_Lambert(B, M) * static_cast<float>(kPi) * L.mean(1);
  }

  // Specular lobe.
  const torch::Tensor F0 = specular_F0(B, M);
  const torch::Tensor k = schlick_k(R);
  torch::Tensor sampled = torch::zeros({P, 3}, opts);
  if (us.size(1) > 0) {
    // GGX half vectors (eq. 18): cos^2 = (1-u)/d, sin^2 = alpha^2 u/d, d = (1-u) + alpha^2 u
    // (the form of render/sampling.cpp, exact for tiny alpha); u kept inside (0,1) so that
    // every square root has a positive argument and a finite gradient.
    const torch::Tensor& u = us;
    const torch::Tensor u1 = comp(u, 0), phi = comp(u, 1) * static_cast<float>(2.0 * kPi);
    const torch::Tensor alpha = (R * R).unsqueeze(1);  // [P,1,1]
    const torch::Tensor d = (1.0 - u1) + alpha * alpha * u1;
    const torch::Tensor cos_h = torch::sqrt((1.0 - u1) / d);
    const torch::Tensor sin_h = alpha * torch::sqrt(u1 / d);
    const torch::Tensor h = torch::cat({sin_h * torch::cos(phi), sin_h * torch::sin(phi), cos_h}, -1);
    const torch::Tensor VoH = dot3(vl.unsqueeze(1), h);
    const torch::Tensor l = 2.0 * VoH * h - vl.unsqueeze(1);
    const torch::Tensor NoL = comp(l, 2);
    const torch::Tensor ok = ((NoL >= kMinCosine) & (VoH > 0.0)).to(opts.dtype());
    const torch::Tensor L = sample_probes(probes, to_world(l));
    // f_s cos / pdf = D F G / (4 NoV NoL) * NoL * 4 VoH / (D NoH) = F G1(NoL) VoH / ((NoV(1-k)+k) NoH)
    const torch::Tensor kk = k.unsqueeze(1);
    const torch::Tensor w = F_SchlickSG(F0.unsqueeze(1), VoH) * G1_SmithSchlick(NoL, kk) *
                            VoH.clamp(0.0, 1.0) / ((NoV.unsqueeze(1) * (1.0 - kk) + kk) * cos_h);
    sampled = (w * L * ok).mean(1);
  }
  // Mirror branch (R < kMirrorRoughness): the delta reflection, weight F(NoV) G1(NoV)^2.
  const torch::Tensor G1v = G1_SmithSchlick(NoV, k);
  const torch::Tensor refl = 2.0 * dot3(v, n) * n - v;
  const torch::Tensor mirror_term =
      F_SchlickSG(F0, NoV) * G1v * G1v * sample_probes(probes, refl.unsqueeze(1)).squeeze(1);
  const torch::Tensor specular = torch::where(R < kMirrorRoughness, mirror_term, sampled);
  return {diffuse * valid_v, specular * valid_v};
}

}  // namespace

namespace {

// The layer's per-pixel tensors: maps [B,C,H,W] -> [P,C], view directions, probes [P,h,w,3].
struct FlatPixels {
  int64_t B, H, W, P;
  torch::Tensor n, v, base, R, M, probes;
};

FlatPixels flatten(const torch::Tensor& normal, const torch::Tensor& base_color, const torch::Tensor& roughness,
                   const torch::Tensor& metalness, const torch::Tensor& probes) {
  FlatPixels f;
  f.B = normal.size(0);
  f.H = normal.size(2);
  f.W = normal.size(3);
  TORCH_CHECK(probes.dim() == 6 && probes.size(0) == f.B && probes.size(1) == f.H && probes.size(2) == f.W &&
                  probes.size(5) == 3,
              "render_layer: probes ", probes.sizes(), " do not match the maps ", normal.sizes());
  f.P = f.B * f.H * f.W;
  auto flat = [&](const torch::Tensor& x) { return x.permute({0, 2, 3, 1}).reshape({f.P, x.size(1)}); };
  f.n = flat(normal);
  f.base = flat(base_color);
  f.R = flat(roughness);
  f.M = flat(metalness);
  f.v = (-pixel_directions(static_cast<int>(f.H), static_cast<int>(f.W), normal.options()))
            .unsqueeze(0)
            .expand({f.B, f.H, f.W, 3})
            .reshape({f.P, 3});
  f.probes = probes.reshape({f.P, probes.size(3), probes.size(4), 3});
  return f;
}

RenderOutput to_images(const FlatPixels& f, const torch::Tensor& diffuse, const torch::Tensor& specular) {
  auto image = [&](const torch::Tensor& x) { return x.view({f.B, f.H, f.W, 3}).permute({0, 3, 1, 2}); };
  RenderOutput out;
  out.diffuse = image(diffuse);
  out.specular = image(specular);
  out.image = out.diffuse + out.specular;
  return out;
}

}  // namespace

RenderOutput render_layer(const torch::Tensor& normal, const torch::Tensor& base_color,
                          const torch::Tensor& roughness, const torch::Tensor& metalness,
                          const torch::Tensor& probes, const RenderSettings& settings) {
  const FlatPixels f = flatten(normal, base_color, roughness, metalness, probes);
  // One draw from torch's generator seeds every pixel's stream: torch::manual_seed reproduces
  // a run, and the generator state saved in a checkpoint resumes it.
  // The draw is on the CPU whatever the device, so a seed gives the same samples everywhere.
  const uint64_t seed = static_cast<uint64_t>(
      torch::randint(std::numeric_limits<int64_t>::max(), {1},
                     torch::TensorOptions().dtype(torch::kLong).device(torch::kCPU))
          .item<int64_t>());
  if (!f.n.device().is_cpu()) {
    // The fused kernel is CPU code: elsewhere the torch-composed estimator runs, on the same
    // uniforms (render_uniforms: pixel p's own stream), so it agrees with the kernel (tested).
    auto [ud, us] = render_uniforms(f.n.size(0), settings.diffuse_samples, settings.specular_samples, seed,
                                    f.n.scalar_type(), static_cast<uint64_t>(settings.first_stream));
    auto [d, s] = render_pixels(f.n, f.v, f.base, f.R, f.M, f.probes, ud.to(f.n.device()), us.to(f.n.device()));
    return to_images(f, d, s);
  }
  const FusedRenderOutput r = render_pixels_fused(f.n, f.v, f.base, f.R, f.M, f.probes, settings.diffuse_samples,
                                                  settings.specular_samples, seed,
                                                  static_cast<uint64_t>(settings.first_stream));
  return to_images(f, r.diffuse, r.specular);
}

RenderOutput render_layer_reference(const torch::Tensor& normal, const torch::Tensor& base_color,
                                    const torch::Tensor& roughness, const torch::Tensor& metalness,
                                    const torch::Tensor& probes, const torch::Tensor& diffuse_uniforms,
                                    const torch::Tensor& specular_uniforms) {
  const FlatPixels f = flatten(normal, base_color, roughness, metalness, probes);
  auto [d, s] = render_pixels(f.n, f.v, f.base, f.R, f.M, f.probes, diffuse_uniforms, specular_uniforms);
  return to_images(f, d, s);
}

// --- Probe warp -------------------------------------------------------------------------------

torch::Tensor warp_probes(const torch::Tensor& probes_q, const torch::Tensor& depth_p,
                          const torch::Tensor& depth_q, const torch::Tensor& dir_p,
                          const torch::Tensor& dir_q) {
  const int64_t B = probes_q.size(0), H = probes_q.size(1), W = probes_q.size(2), h = probes_q.size(3),
                w = probes_q.size(4);
  const torch::Tensor Xp = depth_p.permute({0, 2, 3, 1}) * dir_p.unsqueeze(0);  // [B,H,W,3]
  const torch::Tensor Xq = depth_q.permute({0, 2, 3, 1}) * dir_q.unsqueeze(0);
  const torch::Tensor delta = (Xp - Xq).reshape({B * H * W, 1, 3});
  const torch::Tensor dist2 = dot3(delta, delta);
  // Proxy radius: the view's mean depth, and at least twice the baseline so X_p is inside.
  const torch::Tensor mean_depth = depth_p.mean({1, 2, 3}).detach().view({B, 1, 1});
  const torch::Tensor rho = torch::maximum(mean_depth.expand({B, H * W, 1}).reshape({B * H * W, 1, 1}),
                                           2.0 * safe_sqrt(dist2.detach()));
  const torch::Tensor omega = pixel_directions(static_cast<int>(h), static_cast<int>(w), probes_q.options())
                                  .reshape({1, h * w, 3});
  const torch::Tensor dw = dot3(delta, omega);                        // [P, hw, 1]
  const torch::Tensor disc = dw * dw - dist2 + rho * rho;  // >= rho^2 - |delta|^2 > 0
  const torch::Tensor t = -dw + safe_sqrt(disc);
  const torch::Tensor dir = (delta + t * omega) / rho;  // unit up to rounding
  const torch::Tensor dirn = safe_normalize(dir, omega);
  const torch::Tensor out = sample_probes(probes_q.reshape({B * H * W, h, w, 3}), dirn);
  return out.view({B, H, W, h, w, 3});
}

}  // namespace phyir::model
