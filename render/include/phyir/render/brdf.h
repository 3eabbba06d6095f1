#pragma once
// The UE4 metalness microfacet BRDF of the PhyIR paper, appendix A.3 (Karis 2013):
//   f_r = f_d + f_s,  f_d = B (1 - M) / pi                              (eq. 13)
//   f_s = D F G / (4 (n.v)(n.l))                                        (eq. 14)
//   D   = GGX with alpha = R^2                                          (eq. 15)
//   F   = Schlick with the spherical-Gaussian exponent, F0 = 0.04(1-M)+MB (eq. 16)
//   G   = Smith-Schlick, k = (R+1)^2 / 8                                (eq. 17)
// Importance sampling (eq. 18): cosine-weighted for the diffuse lobe, GGX half-vector
// sampling for the specular lobe, one lobe picked per sample with probability
// specular_probability(); pdf() is the resulting mixture density.
//
// Mirror branch: for roughness below kMirrorRoughness the GGX lobe is replaced by its
// limit, a delta reflection about n carrying F(n.v) * G1(n.v)^2 (the limit of eq. 14-17
// as alpha -> 0 with k = (R+1)^2/8 kept), so nothing divides by alpha.
//
// Energy note: the paper's model adds f_d without a (1 - F) factor, so a dielectric with
// base colour 1 reflects slightly more than 1. We keep it: the network's rendering layer
// must match this BRDF exactly (docs/brdf.md).
//
// All directions are unit vectors in the local shading frame (n = +z), pointing away
// from the surface; wo is the view direction v, wi the light direction l.
#include <glm/glm.hpp>

namespace phyir::render {

// Below this roughness the specular lobe is a mirror (alpha = R^2 < 6.4e-5, a lobe
// narrower than a 0.1 mrad pixel of a 4k panorama, and where float GGX loses precision).
constexpr float kMirrorRoughness = 0.008f;

struct BrdfParams {
  glm::vec3 base_color{0.8f};  // linear
  float roughness = 0.5f;      // perceptual R in [0,1]
  float metalness = 0.0f;      // M in [0,1]
};

// Named terms, each written once.
float D_GGX(float NoH, float alpha);                             // eq. 15
glm::vec3 F_SchlickSG(const glm::vec3& F0, float VoH);           // eq. 16
glm::vec3 specular_F0(const glm::vec3& base_color, float metalness);  // eq. 16, F0
float G1_SmithSchlick(float NoX, float k);                       // eq. 17, one direction
float G_SmithSchlick(float NoV, float NoL, float roughness);     // eq. 17
glm::vec3 Fd_Lambert(const glm::vec3& base_color, float metalness);  // eq. 13

bool is_mirror(float roughness);

// f_r(wo, wi) without the cosine. Zero when either direction is below the surface.
// The mirror lobe (a delta) is not included: it is only reached through sample().
glm::vec3 brdf_eval(const BrdfParams& p, const glm::vec3& wo, const glm::vec3& wi);

// Solid-angle density with which sample() picks wi (non-delta part only).
float brdf_pdf(const BrdfParams& p, const glm::vec3& wo, const glm::vec3& wi);

// Probability that sample() picks the specular lobe (a function of the parameters and
// n.v only, so eval and pdf agree).
float specular_probability(const BrdfParams& p, float NoV);

struct BrdfSample {
  glm::vec3 wi{0.0f};
  glm::vec3 weight{0.0f};  // f_r cos / pdf (for a delta lobe: its reflectance over the lobe choice)
  float pdf = 0.0f;        // solid-angle pdf; for the mirror lobe the lobe-choice probability
  bool delta = false;      // true for the mirror lobe
};

// Draws wi. `u_lobe` picks the lobe, `u` the direction. Returns false (and a zero
// weight) when no valid direction results (wo below the surface, wi below).
bool brdf_sample(const BrdfParams& p, const glm::vec3& wo, float u_lobe, const glm::vec2& u,
                 BrdfSample* out);

// The parameters as every function here uses them: clamped to their documented ranges.
BrdfParams clamped(const BrdfParams& p);

// --- The specular lobe alone (f_s of eq. 14, no f_d) ------------------------------------
// For estimators that take the diffuse lobe's light from elsewhere (a radiance cache).

glm::vec3 specular_eval(const BrdfParams& p, const glm::vec3& wo, const glm::vec3& wi);
// Density of GGX half-vector sampling (eq. 18, specular lobe alone) in wi.
float specular_pdf(const BrdfParams& p, const glm::vec3& wo, const glm::vec3& wi);
// Draws wi by GGX half-vector sampling; *pdf = specular_pdf(p, wo, wi). False when wi is
// below the surface (or p is a mirror, whose lobe is a delta: use brdf_sample).
bool specular_sample(const BrdfParams& p, const glm::vec3& wo, const glm::vec2& u, glm::vec3* wi, float* pdf);

// Directional albedo of the specular lobe alone for F0 = 0 and F0 = 1:
// albedo(F0) = F0 a.x + (1 - F0) a.y, the Fresnel term being linear in F0. From a table
// over (n.v, R) filled once by stratified GGX sampling, bilinear in between.
glm::vec2 specular_albedo_terms(float NoV, float roughness);
// The same for the parameters' own F0.
glm::vec3 specular_albedo(const BrdfParams& p, float NoV);

// f_r averaged over cosine-weighted incident directions: (diffuse + specular albedo) / pi.
// Times an irradiance E it is the radiance reflected towards wo if E arrived uniformly.
glm::vec3 mean_brdf(const BrdfParams& p, float NoV);

}  // namespace phyir::render
