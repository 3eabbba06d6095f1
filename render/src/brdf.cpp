#include "phyir/render/brdf.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "phyir/core/safe_math.h"
#include "phyir/render/sampling.h"

namespace phyir::render {

namespace {

// The smallest alpha D_GGX is ever evaluated with. The BRDF never gets here (roughness
// below kMirrorRoughness takes the mirror branch, and kMirrorRoughness^2 is exactly this
// floor); it only keeps a direct call D_GGX(NoH, 0) finite (1 / (pi alpha^2) ~ 7.8e7)
// instead of 0/0 at NoH = 1.
constexpr float kMinAlpha = kMirrorRoughness * kMirrorRoughness;

// Eq. 15 in terms of cos^2 and sin^2 of theta_h:
//   D = alpha^2 / (pi (cos^2 (alpha^2 - 1) + 1)^2) = alpha^2 / (pi (cos^2 alpha^2 + sin^2)^2).
// Taking sin^2 separately avoids the cancellation in 1 - cos^2 that makes a float NoH
// useless for narrow lobes (NoH = 1 - 6e-8 is one ulp, i.e. a 3.5e-4 rad step).
float ggx_ndf(float cos2, float sin2, float alpha) {
  const float a2 = std::max(alpha, kMinAlpha) * std::max(alpha, kMinAlpha);
  const float d = cos2 * a2 + sin2;
  return a2 / (kPi * d * d);
}

// k = (R + 1)^2 / 8 of eq. 17 (UE4's remapping for analytic lights).
float schlick_k(float roughness) {
  const float r1 = roughness + 1.0f;
  return r1 * r1 / 8.0f;
}

#ifdef PHYIR_BRDF_CYCLES_TERMS
// Cycles 3.4's Principled v1 specular terms, built only for the comparison with Cycles
// (cmake -DPHYIR_BRDF_CYCLES_TERMS=ON, docs/cycles-comparison.md): with them the two
// renderers' materials agree term for term, so what remains between the images is noise or
// a transport difference. The product and the test suite use the paper's terms (#else).

// Exact Smith masking of GGX, one direction: 2 / (1 + sqrt(1 + alpha^2 tan^2)).
float G1_smith_exact(float NoX, float alpha) {
  const float c2 = std::max(NoX * NoX, 1e-12f);
  return 2.0f / (1.0f + std::sqrt(1.0f + alpha * alpha * std::max(1.0f - c2, 0.0f) / c2));
}

float specular_masking(float NoV, float NoL, float roughness) {
  const float alpha = std::max(roughness * roughness, kMinAlpha);
  return G1_smith_exact(NoV, alpha) * G1_smith_exact(NoL, alpha);  // separable, as Cycles 3.4
}

// The mirror limit (alpha -> 0) of the exact masking is 1.
float mirror_masking(float /*NoV*/, float /*roughness*/) { return 1.0f; }

// Unpolarised dielectric Fresnel reflectance at cos(theta) for relative IOR eta.
float fresnel_dielectric(float cosi, float eta) {
  const float c = std::fabs(cosi);
  float g = eta * eta - 1.0f + c * c;
  if (!(g > 0.0f)) return 1.0f;  // total internal reflection
  g = std::sqrt(g);
  const float a = (g - c) / (g + c), b = (c * (g + c) - 1.0f) / (c * (g - c) + 1.0f);
  return 0.5f * a * a * (1.0f + b * b);
}

// Principled v1's "interpolated" Fresnel: the IOR-1.5 dielectric curve rescaled to run from
// F0 (the colour) at normal incidence to white at grazing.
glm::vec3 specular_fresnel(const glm::vec3& F0, float VoH) {
  const float f_normal = fresnel_dielectric(1.0f, 1.5f);
  const float t = (fresnel_dielectric(clamp01(VoH), 1.5f) - f_normal) / (1.0f - f_normal);
  return F0 * (1.0f - t) + glm::vec3(t);
}
#else
float specular_masking(float NoV, float NoL, float roughness) {
  return G_SmithSchlick(NoV, NoL, roughness);  // eq. 17
}

// The alpha -> 0 limit of eq. 17 with k = (R+1)^2/8 kept: G1(NoV)^2.
float mirror_masking(float NoV, float roughness) {
  const float G1 = G1_SmithSchlick(NoV, schlick_k(roughness));
  return G1 * G1;
}

glm::vec3 specular_fresnel(const glm::vec3& F0, float VoH) { return F_SchlickSG(F0, VoH); }  // eq. 16
#endif

// The parameters as the BRDF uses them: clamped to their documented ranges.
using Clamped = BrdfParams;
Clamped clamp_params(const BrdfParams& p) { return clamped(p); }

// Everything eval and pdf need about one (wo, wi) pair, computed once so that
// sample()'s weight is exactly eval * cos / pdf.
struct PairGeometry {
  bool valid = false;
  float NoV = 0.0f, NoL = 0.0f;
  float cos2_h = 0.0f, sin2_h = 0.0f;  // of the half vector
  float NoH = 0.0f, VoH = 0.0f;
};

PairGeometry pair_geometry(const glm::vec3& wo, const glm::vec3& wi) {
  PairGeometry q;
  q.NoV = wo.z;
  q.NoL = wi.z;
  // Directions below (or within kMinCosine of) the horizon contribute nothing.
  if (!(q.NoV >= kMinCosine) || !(q.NoL >= kMinCosine)) return q;
  // h = (wo + wi) / |wo + wi|. wo + wi == wi + wo exactly in floating point, so every
  // quantity below is symmetric in (wo, wi) and eval is reciprocal bit for bit.
  const glm::vec3 s = wo + wi;
  const float len2 = glm::dot(s, s);
  if (!(len2 > 0.0f)) return q;  // unreachable with both z >= kMinCosine
  const float len = std::sqrt(len2);
  q.cos2_h = s.z * s.z / len2;
  q.sin2_h = (s.x * s.x + s.y * s.y) / len2;
  q.NoH = s.z / len;
  // VoH = wo.(wo+wi)/|wo+wi| = (1 + wo.wi)/|wo+wi| = |wo+wi| / 2 for unit vectors.
  // Both z >= kMinCosine gives |wo+wi| >= 2 kMinCosine, so VoH >= kMinCosine.
  q.VoH = std::min(0.5f * len, 1.0f);
  q.valid = true;
  return q;
}

// f_s of eq. 14 (0 for the mirror, a delta reached only through sample()).
glm::vec3 specular_pair(const Clamped& c, const PairGeometry& q) {
  if (!q.valid || is_mirror(c.roughness)) return glm::vec3(0.0f);
  const float alpha = c.roughness * c.roughness;                          // eq. 15
  const float D = ggx_ndf(q.cos2_h, q.sin2_h, alpha);                     // eq. 15
  const glm::vec3 F = specular_fresnel(specular_F0(c.base_color, c.metalness), q.VoH);  // eq. 16
  const float G = specular_masking(q.NoV, q.NoL, c.roughness);                         // eq. 17
  return D * F * G / (4.0f * (q.NoV * q.NoL));                            // eq. 14
}

glm::vec3 eval_pair(const Clamped& c, const PairGeometry& q) {
  if (!q.valid) return glm::vec3(0.0f);
  glm::vec3 f = Fd_Lambert(c.base_color, c.metalness);
  if (is_mirror(c.roughness)) return f;  // the delta lobe is reached only via sample()
  f += specular_pair(c, q);
  return f;
}

// Eq. 18's GGX half-vector sampling as a density in wi: D NoH / (4 VoH) (dwh/dwi = 1 / (4
// VoH) for reflection, Walter et al. 2007, eq. 14), times `scale` (a lobe-choice
// probability) taken first.
float ggx_reflection_pdf(const PairGeometry& q, float alpha, float scale = 1.0f) {
  return scale * ggx_ndf(q.cos2_h, q.sin2_h, alpha) * q.NoH / (4.0f * q.VoH);
}

float pdf_pair(const Clamped& c, float ps, const PairGeometry& q) {
  if (!q.valid) return 0.0f;
  // Eq. 18, mixed with the lobe-choice probability.
  float pdf = (1.0f - ps) * cosine_hemisphere_pdf(q.NoL);
  if (!is_mirror(c.roughness)) pdf += ggx_reflection_pdf(q, c.roughness * c.roughness, ps);
  return pdf;
}

float specular_probability_clamped(const Clamped& c, float NoV) {
  const glm::vec3 diffuse_albedo = c.base_color * (1.0f - c.metalness);
  const float ed = luminance(diffuse_albedo);
  // No diffuse lobe (a metal, or black base colour): always sample the specular lobe, so
  // no sample is wasted on a lobe that returns zero.
  if (!(ed > 0.0f)) return 1.0f;
  // A cheap estimate of the specular albedo: the Fresnel term at normal-to-view.
  const float es = luminance(F_SchlickSG(specular_F0(c.base_color, c.metalness), clamp01(NoV)));
  // Keep both lobes at least 5% likely so neither's tail is starved of samples.
  return std::clamp(es / (es + ed), 0.05f, 0.95f);
}

}  // namespace

// --- Named terms (appendix A.3) ---------------------------------------------------------

float D_GGX(float NoH, float alpha) {
  if (!(NoH > 0.0f)) return 0.0f;  // microfacet normals face up (the chi+ of Walter 2007)
  NoH = std::min(NoH, 1.0f);
  // (1 - NoH)(1 + NoH) is exact for the given NoH, unlike 1 - NoH^2.
  return ggx_ndf(NoH * NoH, (1.0f - NoH) * (1.0f + NoH), alpha);
}

glm::vec3 F_SchlickSG(const glm::vec3& F0, float VoH) {
  // Eq. 16: Schlick's Fresnel with the spherical-Gaussian fit of (1 - VoH)^5 (Karis 2013).
  // Note the fit is not exact at the ends: 2^(-12.538) = 1.68e-4 remains at VoH = 1.
  VoH = clamp01(VoH);
  const float fc = std::exp2((-5.55473f * VoH - 6.98316f) * VoH);
  return F0 + (glm::vec3(1.0f) - F0) * fc;
}

glm::vec3 specular_F0(const glm::vec3& base_color, float metalness) {
  // Eq. 16: 4% reflectance for dielectrics (n = 1.5), the base colour for metals.
  return 0.04f * (1.0f - metalness) + metalness * base_color;
}

float G1_SmithSchlick(float NoX, float k) {
  // Eq. 17, one direction. The denominator is >= k >= 1/8, so this never divides by ~0.
  NoX = clamp01(NoX);
  return NoX / (NoX * (1.0f - k) + k);
}

float G_SmithSchlick(float NoV, float NoL, float roughness) {
  const float k = schlick_k(clamp01(roughness));  // eq. 17
  return G1_SmithSchlick(NoV, k) * G1_SmithSchlick(NoL, k);
}

glm::vec3 Fd_Lambert(const glm::vec3& base_color, float metalness) {
  return base_color * (1.0f - metalness) * kInvPi;  // eq. 13
}

bool is_mirror(float roughness) { return roughness < kMirrorRoughness; }

// --- BRDF ---------------------------------------------------------------------------------

glm::vec3 brdf_eval(const BrdfParams& p, const glm::vec3& wo, const glm::vec3& wi) {
  return eval_pair(clamp_params(p), pair_geometry(wo, wi));
}

float brdf_pdf(const BrdfParams& p, const glm::vec3& wo, const glm::vec3& wi) {
  const Clamped c = clamp_params(p);
  const PairGeometry q = pair_geometry(wo, wi);
  if (!q.valid) return 0.0f;
  return pdf_pair(c, specular_probability_clamped(c, q.NoV), q);
}

float specular_probability(const BrdfParams& p, float NoV) {
  return specular_probability_clamped(clamp_params(p), NoV);
}

bool brdf_sample(const BrdfParams& p, const glm::vec3& wo, float u_lobe, const glm::vec2& u,
                 BrdfSample* out) {
  *out = BrdfSample{};
  const float NoV = wo.z;
  if (!(NoV >= kMinCosine)) return false;
  const Clamped c = clamp_params(p);
  const float ps = specular_probability_clamped(c, NoV);
  const bool mirror = is_mirror(c.roughness);

  glm::vec3 wi;
  if (u_lobe < ps) {
    if (mirror) {
      // The alpha -> 0 limit of eq. 14-17: h = n, VoH = NoL = NoV, and the lobe's
      // integral of f_s cos collapses to F(NoV) G1(NoV)^2 (k keeps its (R+1)^2/8 value).
      out->wi = glm::vec3(-wo.x, -wo.y, wo.z);
      out->weight = specular_fresnel(specular_F0(c.base_color, c.metalness), NoV) *
                    mirror_masking(NoV, c.roughness) / ps;
      out->pdf = ps;
      out->delta = true;
      return true;
    }
    const glm::vec3 h = sample_ggx_half_vector(u, c.roughness * c.roughness);
    wi = 2.0f * glm::dot(wo, h) * h - wo;  // reflect wo about h
    // Renormalise: reflect() of unit vectors is unit only up to rounding.
    wi = safe_normalize(wi, glm::vec3(0.0f, 0.0f, -1.0f));
  } else {
    wi = sample_cosine_hemisphere(u);
  }

  // Half vectors with wo.h < 0 reflect wo below the horizon: those samples (and the
  // kMinCosine band) are lost; brdf_pdf integrates to 1 minus their probability.
  const PairGeometry q = pair_geometry(wo, wi);
  if (!q.valid) return false;
  const float pdf = pdf_pair(c, ps, q);
  if (!(pdf > kTinyDenominator)) return false;
  const glm::vec3 f = eval_pair(c, q);
  out->wi = wi;
  out->pdf = pdf;
  out->weight = f * (q.NoL / pdf);
  out->delta = false;
  return true;
}

BrdfParams clamped(const BrdfParams& p) {
  return {glm::clamp(p.base_color, glm::vec3(0.0f), glm::vec3(1.0f)), clamp01(p.roughness),
          clamp01(p.metalness)};
}

// --- The specular lobe alone ------------------------------------------------------------

glm::vec3 specular_eval(const BrdfParams& p, const glm::vec3& wo, const glm::vec3& wi) {
  return specular_pair(clamp_params(p), pair_geometry(wo, wi));
}

float specular_pdf(const BrdfParams& p, const glm::vec3& wo, const glm::vec3& wi) {
  const Clamped c = clamp_params(p);
  const PairGeometry q = pair_geometry(wo, wi);
  if (!q.valid || is_mirror(c.roughness)) return 0.0f;
  return ggx_reflection_pdf(q, c.roughness * c.roughness);
}

bool specular_sample(const BrdfParams& p, const glm::vec3& wo, const glm::vec2& u, glm::vec3* wi, float* pdf) {
  const float R = clamp01(p.roughness);
  const glm::vec3 h = sample_ggx_half_vector(u, R * R);
  *wi = safe_normalize(2.0f * glm::dot(wo, h) * h - wo, glm::vec3(0, 0, -1));  // reflect wo about h
  *pdf = specular_pdf(p, wo, *wi);
  return *pdf > 0.0f;
}

// --- Specular albedo ----------------------------------------------------------------------

namespace {

struct SpecularAlbedoTable {
  static constexpr int kSize = 32;  // nodes over n.v in [0,1] and R in [0,1]
  std::vector<glm::vec2> terms;     // (F0 = 1, F0 = 0), n.v-major

  SpecularAlbedoTable() : terms(size_t(kSize) * kSize) {
    for (int i = 0; i < kSize; ++i) {
      const float NoV = std::max(float(i) / (kSize - 1), 1e-3f);
      for (int j = 0; j < kSize; ++j) terms[size_t(i) * kSize + j] = integrate(NoV, float(j) / (kSize - 1));
    }
  }

  // The lobe's albedo for F0 = 1 and F0 = 0 at one node.
  static glm::vec2 integrate(float NoV, float R) {
    constexpr int kStrata = 32;  // 32 x 32 stratified GGX samples per node
    if (is_mirror(R)) {
      return glm::vec2(glm::dvec2(specular_fresnel(glm::vec3(1.0f), NoV).x, specular_fresnel(glm::vec3(0.0f), NoV).x) *
                       double(mirror_masking(NoV, R)));
    }
    const glm::vec3 wo(std::sqrt(1.0f - NoV * NoV), 0.0f, NoV);
    const BrdfParams white{glm::vec3(1.0f), R, 1.0f}, black{glm::vec3(0.0f), R, 1.0f};
    glm::dvec2 sum(0.0);
    for (int s = 0; s < kStrata * kStrata; ++s) {
      const glm::vec2 u((s % kStrata + 0.5f) / kStrata, (s / kStrata + 0.5f) / kStrata);
      glm::vec3 wi;
      float pdf;
      if (!specular_sample(white, wo, u, &wi, &pdf)) continue;
      sum += glm::dvec2(brdf_eval(white, wo, wi).x, brdf_eval(black, wo, wi).x) * double(wi.z / pdf);
    }
    return glm::vec2(sum / double(kStrata * kStrata));
  }

  glm::vec2 lookup(float NoV, float R) const {
    const float x = clamp01(NoV) * (kSize - 1), y = clamp01(R) * (kSize - 1);
    const int i = std::min(int(x), kSize - 2), j = std::min(int(y), kSize - 2);
    const float fx = x - i, fy = y - j;
    auto at = [&](int a, int b) { return terms[size_t(a) * kSize + b]; };
    return (1 - fx) * ((1 - fy) * at(i, j) + fy * at(i, j + 1)) +
           fx * ((1 - fy) * at(i + 1, j) + fy * at(i + 1, j + 1));
  }
};

}  // namespace

glm::vec2 specular_albedo_terms(float NoV, float roughness) {
  static const SpecularAlbedoTable table;
  return table.lookup(NoV, roughness);
}

glm::vec3 specular_albedo(const BrdfParams& p, float NoV) {
  const BrdfParams c = clamped(p);
  const glm::vec2 terms = specular_albedo_terms(NoV, c.roughness);
  const glm::vec3 F0 = specular_F0(c.base_color, c.metalness);
  return F0 * terms.x + (glm::vec3(1.0f) - F0) * terms.y;
}

glm::vec3 mean_brdf(const BrdfParams& p, float NoV) {
  const BrdfParams c = clamped(p);
  return Fd_Lambert(c.base_color, c.metalness) + specular_albedo(c, NoV) * kInvPi;
}

}  // namespace phyir::render
