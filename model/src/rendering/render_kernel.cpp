// The rendering layer's fused kernel: forward and a hand-written backward that recomputes each
// sample from the pixel's inputs and its random stream. The maths is render_layer_reference's
// (render_layer.cpp), written per sample; each backward step is the derivative of the forward
// line it mirrors (the comments name them).
#include "render_kernel.h"

#include <ATen/Parallel.h>

// With LibTorch's OpenMP backend (Debian's), at::parallel_for is OpenMP code inlined from
// ATen's headers: compiled without OpenMP it runs the whole loop on the calling thread.
#if AT_PARALLEL_OPENMP && !defined(_OPENMP)
#error "render_kernel.cpp must be compiled with OpenMP (model/CMakeLists.txt), or at::parallel_for is serial"
#endif

#include <algorithm>
#include <cmath>

#include "phyir/core/pcg32.h"
#include "render_layer.h"

namespace phyir::model {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kLn2 = 0.69314718055994530942;
// The uniforms' clamps (as render_layer_reference's): u < 1 keeps sqrt(1 - u) > 0, u in
// (0, 1) keeps the GGX square roots' arguments positive (finite gradients).
constexpr double kDiffuseUMax = 1.0 - 1e-7;
constexpr double kSpecularUMin = 1e-6, kSpecularUMax = 1.0 - 1e-6;

template <typename T>
struct V3 {
  T x, y, z;
};
template <typename T>
inline T dot(const V3<T>& a, const V3<T>& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
template <typename T>
inline void axpy(V3<T>& acc, T s, const V3<T>& a) {  // acc += s a
  acc.x += s * a.x;
  acc.y += s * a.y;
  acc.z += s * a.z;
}

template <typename T>
inline T clamp01(T x) {
  return std::min(std::max(x, T(0)), T(1));
}
// torch::clamp's gradient passes where lo <= x <= hi.
template <typename T>
inline T inside01(T x) {
  return (x >= T(0) && x <= T(1)) ? T(1) : T(0);
}

// Orthonormal frame around n (Duff et al. 2017), as render_layer_reference builds it.
template <typename T>
struct Frame {
  V3<T> n, t, b;
  T sign, a, bb;
  explicit Frame(const V3<T>& nn) : n(nn) {
    sign = n.z >= T(0) ? T(1) : T(-1);
    a = T(-1) / (sign + n.z);
    bb = n.x * n.y * a;
    t = {T(1) + sign * n.x * n.x * a, sign * bb, -sign * n.x};
    b = {bb, sign + n.y * n.y * a, -n.y};
  }
  V3<T> to_world(const V3<T>& l) const {
    return {l.x * t.x + l.y * b.x + l.z * n.x, l.x * t.y + l.y * b.y + l.z * n.y, l.x * t.z + l.y * b.z + l.z * n.z};
  }
  // Gradient of (t, b) onto n: the derivative of the constructor's lines.
  V3<T> backward(const V3<T>& gt, const V3<T>& gb) const {
    const T g_bb = gt.y * sign + gb.x;
    const T a2 = a * a;
    V3<T> g;
    g.x = gt.x * T(2) * sign * n.x * a - gt.z * sign + g_bb * n.y * a;
    g.y = gb.y * T(2) * n.y * a - gb.z + g_bb * n.x * a;
    g.z = gt.x * sign * n.x * n.x * a2 + gb.y * n.y * n.y * a2 + g_bb * n.x * n.y * a2;
    return g;
  }
};

// atan2 and acos for the float kernel: polynomials (max errors 1.7e-6 rad and 2.2e-8 rad, i.e.
// 1e-5 of a 16x32 probe's texel) about 3x cheaper than libm's; double keeps libm (the tests
// compare the double kernel with the torch reference). The backward uses the exact derivatives.
inline float fast_atan2(float y, float x) {
  const float ax = std::abs(x), ay = std::abs(y);
  const float mx = std::max(ax, ay), mn = std::min(ax, ay);
  const float a = mx > 0.0f ? mn / mx : 0.0f;
  const float s = a * a;
  float r = a * (0.99997726f + s * (-0.33262347f + s * (0.19354346f + s * (-0.11643287f + s * (0.05265332f + s * -0.01172120f)))));
  if (ay > ax) r = 1.57079632679f - r;
  if (x < 0.0f) r = 3.14159265359f - r;
  return y < 0.0f ? -r : r;
}
inline float fast_acos(float x) {  // Abramowitz & Stegun 4.4.46
  const float ax = std::abs(x);
  float p = -0.0012624911f;
  p = p * ax + 0.0066700901f;
  p = p * ax - 0.0170881256f;
  p = p * ax + 0.0308918810f;
  p = p * ax - 0.0501743046f;
  p = p * ax + 0.0889789874f;
  p = p * ax - 0.2145988016f;
  p = p * ax + 1.5707963050f;
  const float r = std::sqrt(1.0f - ax) * p;
  return x < 0.0f ? 3.14159265359f - r : r;
}
inline float atan2_k(float y, float x) { return fast_atan2(y, x); }
inline double atan2_k(double y, double x) { return std::atan2(y, x); }
inline float acos_k(float x) { return fast_acos(x); }
inline double acos_k(double x) { return std::acos(x); }

// Bilinear lookup of an h x w equirect probe (wrap in u, clamp in v; texel centres at
// i + 0.5), as sample_probes / equirect_uv, with the derivatives of (u, v) in the direction.
template <typename T>
struct Lookup {
  int64_t i00, i01, i10, i11;  // offsets of the four texels (x3 channels)
  T fx, fy;
  T dudx = 0, dudz = 0, dvdy = 0;

  // derivs: also the derivatives of (u, v) in the direction (backward, for n and R).
  Lookup(const V3<T>& d, int h, int w, bool derivs) {
    const T r2 = d.x * d.x + d.z * d.z;
    const bool safe = r2 > T(kAtan2MinRadius2);  // atan2's gradient is 0/0 on the Y axis
    const T xs = safe ? d.x : T(0), zs = safe ? d.z : T(-1);
    const T u = T(0.5) + atan2_k(xs, -zs) * T(0.5 / kPi);
    const T lo = T(-1.0 + kAcosGradientMargin), hi = T(1.0 - kAcosGradientMargin);  // as safe_acos
    const T yc = std::min(std::max(d.y, lo), hi);
    const T v = acos_k(yc) * T(1.0 / kPi);
    if (derivs && safe) {
      dudx = T(0.5 / kPi) * (-d.z) / r2;
      dudz = T(0.5 / kPi) * d.x / r2;
    }
    if (derivs && d.y >= lo && d.y <= hi) dvdy = T(-1.0 / kPi) / std::sqrt(T(1) - yc * yc);
    const T px = u * T(w) - T(0.5), py = v * T(h) - T(0.5);
    const T x0 = std::floor(px), y0 = std::floor(py);
    fx = px - x0;
    fy = py - y0;
    // The clamp keeps a NaN direction (NaN inputs) inside the probe instead of reading past it.
    const int64_t ix = std::clamp<int64_t>(static_cast<int64_t>(x0), -1, w - 1), iy = static_cast<int64_t>(y0);
    // u in [0, 1] puts ix in [-1, w - 1]: wrap without a division.
    const int64_t ix0 = ix < 0 ? ix + w : (ix >= w ? ix - w : ix);
    const int64_t ix1 = ix0 + 1 >= w ? ix0 + 1 - w : ix0 + 1;
    const int64_t iy0 = std::clamp<int64_t>(iy, 0, h - 1), iy1 = std::clamp<int64_t>(iy + 1, 0, h - 1);
    i00 = (iy0 * w + ix0) * 3;
    i01 = (iy0 * w + ix1) * 3;
    i10 = (iy1 * w + ix0) * 3;
    i11 = (iy1 * w + ix1) * 3;
  }
  void value(const T* p, T* L) const {
    for (int c = 0; c < 3; ++c)
      L[c] = (p[i00 + c] * (T(1) - fx) + p[i01 + c] * fx) * (T(1) - fy) + (p[i10 + c] * (T(1) - fx) + p[i11 + c] * fx) * fy;
  }
  // Adds gL's share to the four texels' gradients; returns the gradient in the direction
  // (when `geometry`; zero otherwise).
  V3<T> backward(const T* p, const T* gL, T* gp, bool geometry) const {
    T gpx = 0, gpy = 0;
    for (int c = 0; c < 3; ++c) {
      gp[i00 + c] += gL[c] * (T(1) - fx) * (T(1) - fy);
      gp[i01 + c] += gL[c] * fx * (T(1) - fy);
      gp[i10 + c] += gL[c] * (T(1) - fx) * fy;
      gp[i11 + c] += gL[c] * fx * fy;
      if (geometry) {
        gpx += gL[c] * ((p[i01 + c] - p[i00 + c]) * (T(1) - fy) + (p[i11 + c] - p[i10 + c]) * fy);
        gpy += gL[c] * ((p[i10 + c] * (T(1) - fx) + p[i11 + c] * fx) - (p[i00 + c] * (T(1) - fx) + p[i01 + c] * fx));
      }
    }
    return {gpx * dudx, gpy * dvdy, gpx * dudz};  // times w and h below
  }
};

template <typename T>
inline T fresnel_weight(T x) {  // F_SchlickSG's exp2 factor, x in [0,1]
  return std::exp2((T(-5.55473) * x - T(6.98316)) * x);
}
template <typename T>
inline T fresnel_weight_grad(T x, T fc) {
  return fc * T(kLn2) * (T(-2.0 * 5.55473) * x - T(6.98316));
}

struct Sizes {
  int h, w, nd, ns;
  uint64_t seed;
  uint64_t first_stream;  // pixel p draws from stream first_stream + p
};

template <typename T>
inline void draw(Pcg32& rng, double lo, double hi, T& u1, T& u2) {
  const float a = rng.next_float();
  const float b = rng.next_float();
  u1 = static_cast<T>(std::min(std::max(static_cast<double>(a), lo), hi));
  u2 = static_cast<T>(std::min(std::max(static_cast<double>(b), lo), hi));
}

// Inputs of one pixel.
template <typename T>
struct PixelIn {
  const T* n;  // 3, unnormalised
  const T* v;  // 3
  const T* B;  // 3
  T R, M;
  const T* probe;  // h*w*3
};

// Gradients of one pixel (backward only).
template <typename T>
struct PixelGrad {
  const T* gd;  // dLoss/d diffuse (3)
  const T* gs;  // dLoss/d specular (3)
  T* gn;        // 3
  T* gB;        // 3
  T* gR;
  T* gM;
  T* gprobe;    // h*w*3
  bool geometry;  // n or R need a gradient: differentiate the sample directions too
};

// The specular lobe's terms of one pixel: F0 = 0.04 (1 - M) + M B and Schlick's k = (R + 1)^2 / 8.
template <typename T>
struct SpecularTerms {
  T F0[3];
  T k;
};

// One GGX half-vector sample (eq. 18): cos^2 = (1-u)/d, sin^2 = alpha^2 u/d, d = (1-u) + alpha^2 u,
// in the pixel's frame, and l, the view direction vl reflected about it.
template <typename T>
struct GgxSample {
  T u1, d, ch, su, sh, cp, sp;
  V3<T> hv, l;
  T VoH, NoL;
};
template <typename T>
inline GgxSample<T> ggx_sample(T u1, T u2, T alpha, T a2, const V3<T>& vl) {
  GgxSample<T> g;
  g.u1 = u1;
  const T phi = u2 * T(static_cast<float>(2.0 * kPi));
  g.d = (T(1) - u1) + a2 * u1;
  g.ch = std::sqrt((T(1) - u1) / g.d);
  g.su = std::sqrt(u1 / g.d);
  g.sh = alpha * g.su;
  g.cp = std::cos(phi);
  g.sp = std::sin(phi);
  g.hv = {g.sh * g.cp, g.sh * g.sp, g.ch};
  g.VoH = dot(vl, g.hv);
  g.l = {T(2) * g.VoH * g.hv.x - vl.x, T(2) * g.VoH * g.hv.y - vl.y, T(2) * g.VoH * g.hv.z - vl.z};
  g.NoL = g.l.z;
  return g;
}

// A GGX sample's weight, F G1(NoL) VoH / ((NoV (1-k) + k) NoH): D cancelled, no division by
// alpha. `common` is its colourless part; qv = NoV (1-k) + k.
template <typename T>
struct GgxWeight {
  T VoHc, fc, NoLc, qL, G1L, den, common;
  T F[3];
};
template <typename T>
inline GgxWeight<T> ggx_weight(const GgxSample<T>& g, const SpecularTerms<T>& sp, T qv) {
  GgxWeight<T> e;
  e.VoHc = std::min(g.VoH, T(1));
  e.fc = fresnel_weight(e.VoHc);
  e.NoLc = std::min(g.NoL, T(1));
  e.qL = e.NoLc * (T(1) - sp.k) + sp.k;
  e.G1L = e.NoLc / e.qL;
  e.den = qv * g.ch;
  e.common = e.G1L * e.VoHc / e.den;
  for (int c = 0; c < 3; ++c) e.F[c] = sp.F0[c] + (T(1) - sp.F0[c]) * e.fc;
  return e;
}

// One pixel's estimate, forward (grad == nullptr: writes out_d, out_s) or backward (accumulates
// into *grad), as named steps: the diffuse samples, the mirror or GGX specular lobe, then the
// pixel-level backward through the material and the geometry. The gradients of the pixel's
// intermediate quantities are accumulated in its members over the samples. Built on the stack
// per pixel; every step is inline (no allocation, no virtual call).
template <typename T>
class PixelShader {
 public:
  PixelShader(const PixelIn<T>& in, const Sizes& sz, const PixelGrad<T>* grad)
      : in_(in),
        sz_(sz),
        grad_(grad),
        h_(sz.h),
        w_(sz.w),
        R_(clamp01(in.R)),
        M_(clamp01(in.M)),
        m_{in.n[0], in.n[1], in.n[2]},
        len2_(dot(m_, m_)),
        inv_len_(T(1) / std::sqrt(std::max(len2_, T(kNormalMinLength2)))),
        n_{m_.x * inv_len_, m_.y * inv_len_, m_.z * inv_len_},
        fr_(n_),
        v_{in.v[0], in.v[1], in.v[2]},
        vl_{dot(v_, fr_.t), dot(v_, fr_.b), dot(v_, n_)},
        geo_(grad && grad->geometry) {
    for (int c = 0; c < 3; ++c) B_[c] = clamp01(in.B[c]);
  }

  // As render::brdf_eval: a surface seen from below (or within kMinCosine of grazing) is black.
  bool faces_viewer() const { return vl_.z >= T(kMinCosine); }

  // --- Diffuse: cosine samples, f_d L cos / pdf = B (1 - M) L (eq. 18) ---
  void diffuse(Pcg32& rng, T* out_d) {
    if (sz_.nd <= 0) return;
    T sumL[3] = {0, 0, 0}, L[3];
    const T scale = T(1) / T(sz_.nd);
    T kd[3];  // dLoss/dL of one sample
    if (grad_)
      for (int c = 0; c < 3; ++c) kd[c] = grad_->gd[c] * B_[c] * (T(1) - M_) * scale;
    for (int s = 0; s < sz_.nd; ++s) {
      T u1, u2;
      draw(rng, 0.0, kDiffuseUMax, u1, u2);
      const T phi = u2 * T(static_cast<float>(2.0 * kPi));
      const T r = std::sqrt(u1), z = std::sqrt(T(1) - u1);
      if (!(z >= T(kMinCosine))) continue;
      const V3<T> l{r * std::cos(phi), r * std::sin(phi), z};
      const Lookup<T> lk(fr_.to_world(l), h_, w_, geo_);
      lk.value(in_.probe, L);
      for (int c = 0; c < 3; ++c) sumL[c] += L[c];
      if (grad_) {
        const V3<T> gw = direction_grad(lk.backward(in_.probe, kd, grad_->gprobe, geo_));
        if (geo_) to_world_backward(l, gw);
      }
    }
    for (int c = 0; c < 3; ++c) {
      const T meanL = sumL[c] * scale;
      if (!grad_) {
        out_d[c] = B_[c] * (T(1) - M_) * meanL;
      } else {
        gBc_[c] += grad_->gd[c] * (T(1) - M_) * meanL;
        *grad_->gM -= grad_->gd[c] * B_[c] * meanL * inside01(in_.M);
      }
    }
  }

  // --- Specular: the mirror below kMirrorRoughness, else GGX samples ---
  void specular(Pcg32& rng, T* out_s) {
    SpecularTerms<T> sp;
    for (int c = 0; c < 3; ++c) sp.F0[c] = T(0.04) * (T(1) - M_) + M_ * B_[c];
    sp.k = (R_ + T(1)) * (R_ + T(1)) / T(8);
    if (R_ < T(kMirrorRoughness))
      mirror(sp, out_s);
    else if (sz_.ns > 0)
      ggx(sp, rng, out_s);
  }

  // --- Pixel-level backward: F0, k, alpha, NoV, vl, frame, normalisation ---
  void backward_to_inputs() {
    material_backward();
    if (geo_) geometry_backward();
  }

 private:
  // Mirror: the delta reflection F(NoV) G1(NoV)^2 L(reflect(v, n)).
  void mirror(const SpecularTerms<T>& sp, T* out_s) {
    const T VoN = dot(v_, n_);
    const V3<T> refl{T(2) * VoN * n_.x - v_.x, T(2) * VoN * n_.y - v_.y, T(2) * VoN * n_.z - v_.z};
    const Lookup<T> lk(refl, h_, w_, geo_);
    T L[3];
    lk.value(in_.probe, L);
    const T NoV = no_v();
    const T fc = fresnel_weight(NoV);
    const T q = NoV * (T(1) - sp.k) + sp.k;
    const T G1 = NoV / q;
    T Fv[3];
    for (int c = 0; c < 3; ++c) Fv[c] = sp.F0[c] + (T(1) - sp.F0[c]) * fc;
    if (!grad_) {
      for (int c = 0; c < 3; ++c) out_s[c] = Fv[c] * G1 * G1 * L[c];
      return;
    }
    T gL[3], gfc = 0, gG1 = 0;
    for (int c = 0; c < 3; ++c) {
      gL[c] = grad_->gs[c] * Fv[c] * G1 * G1;
      const T gF = grad_->gs[c] * G1 * G1 * L[c];
      gF0_[c] += gF * (T(1) - fc);
      gfc += gF * (T(1) - sp.F0[c]);
      gG1 += grad_->gs[c] * Fv[c] * T(2) * G1 * L[c];
    }
    gNoV_ += gfc * fresnel_weight_grad(NoV, fc) + gG1 * sp.k / (q * q);
    gk_ += gG1 * (-NoV * (T(1) - NoV)) / (q * q);
    const V3<T> gr = direction_grad(lk.backward(in_.probe, gL, grad_->gprobe, geo_));
    if (geo_) {  // refl = 2 (v.n) n - v
      axpy(gn_, T(2) * VoN, gr);
      axpy(gn_, T(2) * dot(gr, n_), v_);
    }
  }

  // GGX half vectors, each sample weighted by ggx_weight.
  void ggx(const SpecularTerms<T>& sp, Pcg32& rng, T* out_s) {
    const T alpha = R_ * R_, a2 = alpha * alpha;
    const T scale = T(1) / T(sz_.ns);
    const T qv = no_v() * (T(1) - sp.k) + sp.k;
    T sum[3] = {0, 0, 0}, L[3];
    for (int s = 0; s < sz_.ns; ++s) {
      T u1, u2;
      draw(rng, kSpecularUMin, kSpecularUMax, u1, u2);
      const GgxSample<T> g = ggx_sample(u1, u2, alpha, a2, vl_);
      if (!(g.NoL >= T(kMinCosine) && g.VoH > T(0))) continue;  // reflected below the horizon: 0
      const Lookup<T> lk(fr_.to_world(g.l), h_, w_, geo_);
      lk.value(in_.probe, L);
      const GgxWeight<T> e = ggx_weight(g, sp, qv);
      if (!grad_) {
        for (int c = 0; c < 3; ++c) sum[c] += e.F[c] * e.common * L[c];
        continue;
      }
      ggx_sample_backward(g, e, lk, L, sp, scale, qv, alpha, a2);
    }
    if (!grad_)
      for (int c = 0; c < 3; ++c) out_s[c] = sum[c] * scale;
  }

  // Backward of: sum_c += F_c common L_c (scaled by 1/Ns).
  void ggx_sample_backward(const GgxSample<T>& g, const GgxWeight<T>& e, const Lookup<T>& lk, const T* L,
                           const SpecularTerms<T>& sp, T scale, T qv, T alpha, T a2) {
    T gL[3], gcommon = 0, gfc = 0;
    for (int c = 0; c < 3; ++c) {
      const T a = grad_->gs[c] * scale;
      gL[c] = a * e.F[c] * e.common;
      const T gF = a * e.common * L[c];
      gF0_[c] += gF * (T(1) - e.fc);
      gfc += gF * (T(1) - sp.F0[c]);
      gcommon += a * e.F[c] * L[c];
    }
    // common = G1L VoHc / den
    const T gG1L = gcommon * e.VoHc / e.den;
    const T gVoHc = gcommon * e.G1L / e.den + gfc * fresnel_weight_grad(e.VoHc, e.fc);
    const T gden = -gcommon * e.common / e.den;
    // G1L = NoLc / (NoLc (1-k) + k);  den = (NoV (1-k) + k) ch
    const T gNoLc = gG1L * sp.k / (e.qL * e.qL);
    gk_ += gG1L * (-e.NoLc * (T(1) - e.NoLc)) / (e.qL * e.qL) + gden * (T(1) - no_v()) * g.ch;
    gNoV_ += gden * (T(1) - sp.k) * g.ch;
    const T gch = gden * qv;
    const V3<T> gw = direction_grad(lk.backward(in_.probe, gL, grad_->gprobe, geo_));
    if (geo_) ggx_direction_backward(g, gw, gVoHc, gNoLc, gch, alpha, a2);
  }

  // The sample direction's share: through l to the frame, the half vector and alpha.
  void ggx_direction_backward(const GgxSample<T>& g, const V3<T>& gw, T gVoHc, T gNoLc, T gch, T alpha, T a2) {
    to_world_backward(g.l, gw);
    V3<T> gl{dot(gw, fr_.t), dot(gw, fr_.b), dot(gw, n_)};
    gl.z += g.NoL <= T(1) ? gNoLc : T(0);
    // l = 2 VoH hv - vl
    T gVoH = (g.VoH <= T(1) ? gVoHc : T(0)) + T(2) * dot(gl, g.hv);
    V3<T> ghv{T(2) * g.VoH * gl.x, T(2) * g.VoH * gl.y, T(2) * g.VoH * gl.z};
    axpy(gvl_, T(-1), gl);
    // VoH = vl . hv
    axpy(gvl_, gVoH, g.hv);
    axpy(ghv, gVoH, vl_);
    // hv = (sh cos phi, sh sin phi, ch); ch, sh functions of alpha
    const T gsh = ghv.x * g.cp + ghv.y * g.sp;
    gch += ghv.z;
    galpha_ += gch * (-g.ch * alpha * g.u1 / g.d) + gsh * g.su * (T(1) - a2 * g.u1 / g.d);
  }

  // F0, k and alpha onto base colour, metalness and roughness (through their clamps).
  void material_backward() {
    for (int c = 0; c < 3; ++c) {
      gBc_[c] += gF0_[c] * M_;
      *grad_->gM += gF0_[c] * (B_[c] - T(0.04)) * inside01(in_.M);
      grad_->gB[c] += gBc_[c] * inside01(in_.B[c]);
    }
    *grad_->gR += (galpha_ * T(2) * R_ + gk_ * (R_ + T(1)) / T(4)) * inside01(in_.R);
  }

  // NoV and vl onto the frame, the frame onto n, n onto the unnormalised normal.
  void geometry_backward() {
    if (vl_.z <= T(1)) gvl_.z += gNoV_;  // NoV = clamp(vl.z, kMinCosine, 1)
    // vl = (v.t, v.b, v.n)
    axpy(gt_, gvl_.x, v_);
    axpy(gb_, gvl_.y, v_);
    axpy(gn_, gvl_.z, v_);
    const V3<T> gf = fr_.backward(gt_, gb_);
    gn_.x += gf.x;
    gn_.y += gf.y;
    gn_.z += gf.z;
    // n = m / sqrt(max(|m|^2, kNormalMinLength2))
    if (len2_ >= T(kNormalMinLength2)) {
      const T ng = dot(n_, gn_);
      grad_->gn[0] += (gn_.x - n_.x * ng) * inv_len_;
      grad_->gn[1] += (gn_.y - n_.y * ng) * inv_len_;
      grad_->gn[2] += (gn_.z - n_.z * ng) * inv_len_;
    } else {
      grad_->gn[0] += gn_.x * inv_len_;
      grad_->gn[1] += gn_.y * inv_len_;
      grad_->gn[2] += gn_.z * inv_len_;
    }
  }

  T no_v() const { return std::min(vl_.z, T(1)); }
  // A lookup's direction gradient is per texel: times w and h.
  V3<T> direction_grad(const V3<T>& g) const { return V3<T>{g.x * T(w_), g.y * T(h_), g.z * T(w_)}; }
  void to_world_backward(const V3<T>& l, const V3<T>& gw) {  // wd = l.x t + l.y b + l.z n
    axpy(gt_, l.x, gw);
    axpy(gb_, l.y, gw);
    axpy(gn_, l.z, gw);
  }

  const PixelIn<T>& in_;
  const Sizes& sz_;
  const PixelGrad<T>* grad_;
  const int h_, w_;
  T B_[3];
  const T R_, M_;
  const V3<T> m_;
  const T len2_, inv_len_;
  const V3<T> n_;
  const Frame<T> fr_;
  const V3<T> v_, vl_;
  const bool geo_;  // n or R need a gradient: differentiate the sample directions too
  // Gradients accumulated over the samples.
  T gBc_[3] = {0, 0, 0}, gF0_[3] = {0, 0, 0};
  V3<T> gt_{0, 0, 0}, gb_{0, 0, 0}, gn_{0, 0, 0}, gvl_{0, 0, 0};
  T gNoV_ = 0, gk_ = 0, galpha_ = 0;
};

template <typename T>
void shade_pixel(const PixelIn<T>& in, const Sizes& sz, uint64_t pixel, T* out_d, T* out_s,
                 const PixelGrad<T>* grad) {
  PixelShader<T> shader(in, sz, grad);
  if (!grad) {
    for (int c = 0; c < 3; ++c) out_d[c] = out_s[c] = T(0);
  }
  if (!shader.faces_viewer()) return;
  Pcg32 rng(mix64(sz.seed), sz.first_stream + pixel);
  shader.diffuse(rng, out_d);
  shader.specular(rng, out_s);
  if (grad) shader.backward_to_inputs();
}

struct Inputs {
  torch::Tensor n, v, B, R, M, probes;
};

Inputs contiguous(const torch::Tensor& n, const torch::Tensor& v, const torch::Tensor& B, const torch::Tensor& R,
                  const torch::Tensor& M, const torch::Tensor& probes) {
  const auto dt = n.scalar_type();
  auto c = [dt](const torch::Tensor& x) { return x.detach().to(dt).contiguous(); };
  return {c(n), c(v), c(B), c(R), c(M), c(probes)};
}

// Fewer pixels than this per thread are not worth a thread.
constexpr int64_t kGrain = 16;
// at::parallel_for gives each thread one contiguous share of the range, and pixels differ in
// cost by region (back-facing ones stop early, mirrors take one specular lookup, samples
// below the horizon skip theirs). Task t renders pixel (t % kBands) * band + t / kBands, a
// column-major walk of a kBands x band grid: every thread's share spans all kBands bands.
constexpr int64_t kBands = 64;

// Calls fn(p) for every pixel p in [0, P), on at::parallel_for's threads; each pixel is
// independent of the others, so the split does not change the result.
template <typename Fn>
void for_each_pixel(int64_t P, const Fn& fn) {
  const int64_t band = (P + kBands - 1) / kBands;
  at::parallel_for(0, band * kBands, kGrain, [&](int64_t b, int64_t e) {
    for (int64_t t = b; t < e; ++t) {
      const int64_t p = (t % kBands) * band + t / kBands;
      if (p < P) fn(p);  // the grid's last band may be short
    }
  });
}

template <typename T>
PixelIn<T> pixel_in(const Inputs& x, int64_t p, int64_t probe_stride) {
  return {x.n.data_ptr<T>() + 3 * p, x.v.data_ptr<T>() + 3 * p, x.B.data_ptr<T>() + 3 * p,
          x.R.data_ptr<T>()[p],      x.M.data_ptr<T>()[p],      x.probes.data_ptr<T>() + probe_stride * p};
}

FusedRenderOutput forward_impl(const Inputs& x, const Sizes& sz) {
  const int64_t P = x.n.size(0), stride = int64_t(sz.h) * sz.w * 3;
  FusedRenderOutput out{torch::empty({P, 3}, x.n.options()), torch::empty({P, 3}, x.n.options())};
  AT_DISPATCH_FLOATING_TYPES(x.n.scalar_type(), "render_pixels_fused", [&] {
    scalar_t* d = out.diffuse.data_ptr<scalar_t>();
    scalar_t* s = out.specular.data_ptr<scalar_t>();
    for_each_pixel(P, [&](int64_t p) {
      shade_pixel<scalar_t>(pixel_in<scalar_t>(x, p, stride), sz, static_cast<uint64_t>(p), d + 3 * p, s + 3 * p,
                            nullptr);
    });
  });
  return out;
}

struct Grads {
  torch::Tensor n, B, R, M, probes;
};

Grads backward_impl(const Inputs& x, const Sizes& sz, const torch::Tensor& gd_in, const torch::Tensor& gs_in,
                    bool geometry) {
  const int64_t P = x.n.size(0), stride = int64_t(sz.h) * sz.w * 3;
  const auto opts = x.n.options();
  auto grad_or_zero = [&](const torch::Tensor& g) {
    return g.defined() ? g.to(x.n.scalar_type()).contiguous() : torch::zeros({P, 3}, opts);
  };
  const torch::Tensor gd = grad_or_zero(gd_in), gs = grad_or_zero(gs_in);
  Grads g{torch::zeros({P, 3}, opts), torch::zeros({P, 3}, opts), torch::zeros({P, 1}, opts),
          torch::zeros({P, 1}, opts), torch::zeros_like(x.probes)};
  AT_DISPATCH_FLOATING_TYPES(x.n.scalar_type(), "render_pixels_fused_backward", [&] {
    const scalar_t* pgd = gd.data_ptr<scalar_t>();
    const scalar_t* pgs = gs.data_ptr<scalar_t>();
    scalar_t *gn = g.n.data_ptr<scalar_t>(), *gB = g.B.data_ptr<scalar_t>(), *gR = g.R.data_ptr<scalar_t>(),
             *gM = g.M.data_ptr<scalar_t>(), *gp = g.probes.data_ptr<scalar_t>();
    for_each_pixel(P, [&](int64_t p) {
      const PixelGrad<scalar_t> pg{pgd + 3 * p, pgs + 3 * p, gn + 3 * p, gB + 3 * p, gR + p, gM + p,
                                   gp + stride * p, geometry};
      shade_pixel<scalar_t>(pixel_in<scalar_t>(x, p, stride), sz, static_cast<uint64_t>(p), nullptr, nullptr, &pg);
    });
  });
  return g;
}

using torch::autograd::AutogradContext;
using torch::autograd::variable_list;

struct FusedRenderFunction : torch::autograd::Function<FusedRenderFunction> {
  static variable_list forward(AutogradContext* ctx, const torch::Tensor& n, const torch::Tensor& v,
                               const torch::Tensor& B, const torch::Tensor& R, const torch::Tensor& M,
                               const torch::Tensor& probes, int64_t nd, int64_t ns, int64_t seed,
                               int64_t first_stream) {
    const Inputs x = contiguous(n, v, B, R, M, probes);
    const Sizes sz{static_cast<int>(probes.size(1)), static_cast<int>(probes.size(2)), static_cast<int>(nd),
                   static_cast<int>(ns), static_cast<uint64_t>(seed), static_cast<uint64_t>(first_stream)};
    // Only the inputs are kept: backward recomputes every sample from them and the seed.
    ctx->save_for_backward({x.n, x.v, x.B, x.R, x.M, x.probes});
    ctx->saved_data["nd"] = nd;
    ctx->saved_data["ns"] = ns;
    ctx->saved_data["seed"] = seed;
    ctx->saved_data["first_stream"] = first_stream;
    const FusedRenderOutput out = forward_impl(x, sz);
    return {out.diffuse, out.specular};
  }

  static variable_list backward(AutogradContext* ctx, variable_list grad_out) {
    const auto saved = ctx->get_saved_variables();
    const Inputs x{saved[0], saved[1], saved[2], saved[3], saved[4], saved[5]};
    const Sizes sz{static_cast<int>(x.probes.size(1)), static_cast<int>(x.probes.size(2)),
                   static_cast<int>(ctx->saved_data["nd"].toInt()), static_cast<int>(ctx->saved_data["ns"].toInt()),
                   static_cast<uint64_t>(ctx->saved_data["seed"].toInt()),
                   static_cast<uint64_t>(ctx->saved_data["first_stream"].toInt())};
    // The sample directions' derivatives are the costly part: only when n or R need them.
    const bool geometry = ctx->needs_input_grad(0) || ctx->needs_input_grad(3);
    const Grads g = backward_impl(x, sz, grad_out[0], grad_out[1], geometry);
    return {g.n,           torch::Tensor(), g.B,           g.R,           g.M, g.probes, torch::Tensor(),
            torch::Tensor(), torch::Tensor(), torch::Tensor()};
  }
};

}  // namespace

FusedRenderOutput render_pixels_fused(const torch::Tensor& n, const torch::Tensor& v,
                                      const torch::Tensor& base_color, const torch::Tensor& roughness,
                                      const torch::Tensor& metalness, const torch::Tensor& probes,
                                      int diffuse_samples, int specular_samples, uint64_t seed,
                                      uint64_t first_stream) {
  TORCH_CHECK(n.dim() == 2 && n.size(1) == 3 && probes.dim() == 4 && probes.size(0) == n.size(0) &&
                  probes.size(3) == 3,
              "render_pixels_fused: n ", n.sizes(), " and probes ", probes.sizes(), " do not match");
  const auto out = FusedRenderFunction::apply(n, v, base_color, roughness, metalness, probes, diffuse_samples,
                                              specular_samples, static_cast<int64_t>(seed),
                                              static_cast<int64_t>(first_stream));
  return {out[0], out[1]};
}

std::pair<torch::Tensor, torch::Tensor> render_uniforms(int64_t pixels, int nd, int ns, uint64_t seed,
                                                        torch::Dtype dtype, uint64_t first_stream) {
  torch::Tensor ud = torch::empty({pixels, nd, 2}, torch::kDouble);
  torch::Tensor us = torch::empty({pixels, ns, 2}, torch::kDouble);
  double* pd = ud.data_ptr<double>();
  double* ps = us.data_ptr<double>();
  for (int64_t p = 0; p < pixels; ++p) {
    Pcg32 rng(mix64(seed), first_stream + static_cast<uint64_t>(p));
    for (int s = 0; s < nd; ++s) draw(rng, 0.0, kDiffuseUMax, pd[(p * nd + s) * 2], pd[(p * nd + s) * 2 + 1]);
    for (int s = 0; s < ns; ++s)
      draw(rng, kSpecularUMin, kSpecularUMax, ps[(p * ns + s) * 2], ps[(p * ns + s) * 2 + 1]);
  }
  return {ud.to(dtype), us.to(dtype)};
}

}  // namespace phyir::model
