#pragma once
// The light point and spot lights throw on the surfaces close to them, in the probes.
// Internal to the probe renderer (docs/probes.md, "Photons round point and spot lights").
#include <cstdint>
#include <vector>

#include "phyir/render/render_scene.h"

namespace phyir::render {

// A bulb 4 cm under a ceiling lights a disc of it round the fixture tens of times brighter
// than anything else a floor probe sees, in a sliver of one texel: the texel's directions
// find it by chance. Photons find it by construction: directions from the light, stratified
// over its sphere (a spot's cone), traced to their first hit, each joined to a probe's
// origin by one shadow ray. Both estimate the diffuse light reflected at the first hits of a
// texel's directions (highlights stay with the directions), and are combined by multiple
// importance sampling: at a hit where N photons land per texel solid angle, the photons take
// N / (16 spp + N) of each light's diffuse light and the texel's spp directions the rest (the balance heuristic, a photon counted as a 16th of
// a direction; below 16 photons per texel the directions take it all).
class PunctualPhotons {
 public:
  PunctualPhotons() = default;
  static constexpr int kMaxLights = 8;  // the scenes whose punctual lights TexelEstimator takes exactly

  // `per_light` photons (rounded to a square) from each point and spot light; none with
  // per_light = 0, or with more than kMaxLights punctual lights. `spp`: a texel's directions,
  // for the weights. Traces them (counted in *rays).
  PunctualPhotons(const RenderScene& scene, int per_light, int spp, uint64_t seed, uint64_t* rays);

  bool empty() const { return photons_.empty(); }
  size_t size() const { return photons_.size(); }

  // The share of each light's diffuse light (shares[light], kMaxLights of them) at `position`
  // (geometric normal `ng`), the first hit of a direction from `origin` inside a texel of
  // solid angle `texel_solid_angle`, that the photons take; false where they take none.
  bool shares(const glm::vec3& origin, const glm::vec3& position, const glm::vec3& ng, float texel_solid_angle,
              float* shares) const;

  // The photons' estimate for one probe of h x w texels: radiance per texel (row-major) into
  // `radiance`, and the same times max(0, d . normal) into `radiance_cos`; both are resized
  // and zeroed first. About kPhotonsKeptPerTexel photons of a texel are joined to the probe,
  // chosen by `key`. Shadow rays counted in *rays.
  void gather(const glm::vec3& origin, const glm::vec3& normal, int height, int width, uint64_t key,
              std::vector<glm::vec3>* radiance, std::vector<glm::vec3>* radiance_cos, uint64_t* rays) const;

 private:
  struct Source {
    int light = -1;
    glm::vec3 position{0.0f};
    glm::vec3 axis{0.0f, 0.0f, -1.0f};  // a spot's
    float cos_outer = -1.0f;            // -1: the whole sphere
    float photons_per_steradian = 0.0f; // photons x their density in direction
  };
  struct Photon {
    SurfaceInteraction hit;
    int source = 0;
    glm::vec3 to_light{0.0f};   // unit
    glm::vec3 irradiance{0.0f}; // on a surface facing the light (DeltaIllumination)
  };

  // A photon's estimate of its texel's radiance if nothing hides it from `origin` (0 where
  // the texel's directions take its hit), and that texel (row-major).
  glm::vec3 unoccluded(const Photon& p, const glm::vec3& origin, int height, int width, uint32_t* texel) const;
  // Whether nothing hides the photon's hit from `origin` (one shadow ray, counted).
  bool visible(const Photon& p, const glm::vec3& origin, uint64_t* rays) const;
  // The photons' share of a hit where they land at this density times the texel's solid angle.
  float share(float photons_per_texel) const;
  // Photons landing per unit of a probe's solid angle round the direction to `position`.
  float photons_per_steradian(const Source& s, const glm::vec3& origin, const glm::vec3& position,
                              const glm::vec3& ng) const;

  std::vector<Source> sources_;
  std::vector<Photon> photons_;
  const RenderScene* scene_ = nullptr;
  float spp_ = 1.0f;
};

}  // namespace phyir::render
