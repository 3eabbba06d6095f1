#pragma once
// Photons for the light of point, spot and directional lights on the surfaces the probes see.
// Internal to the probe renderer (docs/probes-estimator.md, "Photons round punctual lights and the sun").
#include <cstdint>
#include <vector>

#include "phyir/render/render_scene.h"
#include "phyir/render/rng.h"

namespace phyir::render {

// Photons traced from each light to their first hit find by construction what a texel's
// directions find by chance (a bulb's halo, a sun patch's rim). Where N land per texel they take
// N / (16 spp + N) of a light's diffuse light (balance heuristic; none below 16), directions the rest.
class PunctualPhotons {
 public:
  PunctualPhotons() = default;
  static constexpr int kMaxLights = 8;  // the scenes whose punctual lights TexelEstimator takes exactly

  // `per_light` photons (rounded to a square) from each point or spot light, per square metre of
  // beam from the sun, kept inside `region`; none if per_light = 0 or over kMaxLights lights.
  // `spp`: a texel's directions, for the weights. Rays counted in *rays.
  PunctualPhotons(const RenderScene& scene, int per_light, int spp, const scenes::Bounds& region, uint64_t seed,
                  uint64_t* rays);

  bool empty() const { return photons_.empty(); }
  size_t size() const { return photons_.size(); }

  // The share of each light's diffuse light (shares[light], kMaxLights of them) at `position`
  // (geometric normal `ng`), the first hit of a direction from `origin` inside a texel of
  // solid angle `texel_solid_angle`, that the photons take; false where they take none.
  bool shares(const glm::vec3& origin, const glm::vec3& position, const glm::vec3& ng, float texel_solid_angle,
              float* shares) const;

  // The photons' estimate for an h x w probe: radiance per texel (row-major) into `radiance`,
  // times max(0, d . normal) into `radiance_cos` (both resized, zeroed); about kPhotonsKeptPerTexel
  // per texel joined (chosen by `key`, shadow rays in *rays). `scale` (optional, per texel):
  // multiplies the count for the share, as TexelEstimator::sample does; 0 skips the texel.
  void gather(const glm::vec3& origin, const glm::vec3& normal, int height, int width, uint64_t key,
              std::vector<glm::vec3>* radiance, std::vector<glm::vec3>* radiance_cos, uint64_t* rays,
              const std::vector<float>* scale = nullptr) const;

 private:
  // The sun's beam: a square of cells over region_, upstream; per cell photons/m^2 (0: none got in).
  struct Beam {
    glm::vec3 centre{0.0f}, t{1.0f, 0.0f, 0.0f}, b{0.0f, 1.0f, 0.0f};  // t, b: across the beam
    float half_width = 0.0f, upstream = 0.0f;
    std::vector<float> density;  // per cell, row-major
    // A photon's ray from point u (unit square) of a cell; -1 from cell_of: outside the square.
    Ray ray(int cell, const glm::vec2& u, const glm::vec3& axis) const;
    int cell_of(const glm::vec3& point) const;
  };
  struct Source {
    int light = -1;
    bool directional = false;
    glm::vec3 position{0.0f};           // a point's or spot's
    glm::vec3 axis{0.0f, 0.0f, -1.0f};  // a spot's; the sun's direction of travel
    float cos_outer = -1.0f;            // -1: the whole sphere
    float density = 0.0f;               // a point's or spot's photons per steradian
    Beam beam;                          // the sun's
  };
  struct Photon {
    SurfaceInteraction hit;
    int source = 0;
    glm::vec3 to_light{0.0f};   // unit
    glm::vec3 irradiance{0.0f}; // on a surface facing the light (DeltaIllumination)
  };

  // Stratified photons from point or spot light i (its sphere or cone) or the sun (its cells).
  void trace_from_light(int i, int per_light, uint64_t seed, uint64_t* rays);
  void trace_from_sun(int i, int per_square_metre, uint64_t seed, uint64_t* rays);
  // The sun's cells whose pilot photons land in region_, and their neighbours.
  std::vector<int> cells_reaching_region(const Source& s, Rng* rng, uint64_t* rays) const;
  // Traces one photon, kept where it lands on a surface the light reaches (the sun's in region_).
  void trace_photon(const Ray& ray, int source, uint64_t* rays);
  // A photon's estimate of its texel's radiance if nothing hides it from `origin` (0 where
  // the texel's directions take its hit), and that texel (row-major).
  glm::vec3 unoccluded(const Photon& p, const glm::vec3& origin, int height, int width, const std::vector<float>* scale,
                       uint32_t* texel) const;
  // Whether nothing hides the photon's hit from `origin` (one shadow ray, counted).
  bool visible(const Photon& p, const glm::vec3& origin, uint64_t* rays) const;
  // The photons' share of a hit where they land at this density times the texel's solid angle.
  float share(float photons_per_texel) const;
  // Photons landing per unit of a probe's solid angle round the direction to `position`.
  float photons_per_steradian(const Source& s, const glm::vec3& origin, const glm::vec3& position,
                              const glm::vec3& ng) const;

  bool in_region(const glm::vec3& p) const;

  std::vector<Source> sources_;
  std::vector<Photon> photons_;
  const RenderScene* scene_ = nullptr;
  scenes::Bounds region_;  // where the sun's photons are kept
  float spp_ = 1.0f;
};

}  // namespace phyir::render
