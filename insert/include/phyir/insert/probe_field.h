#pragma once
// A view's probe grid as light that varies with position (render::PositionalRadiance): a
// world point is projected into the panorama from the camera, and the radiance arriving there
// from a direction is the bilinear blend, over the four grid cells around that projection, of
// the valid probes' texels in that direction (invalid probes take no weight). Where none of the
// four is valid, the nearest valid probe of the grid along the row, then anywhere.
#include <glm/glm.hpp>

#include <memory>
#include <vector>

#include "phyir/render/environment_light.h"
#include "phyir/view/probe_mosaic.h"

namespace phyir::insert {

inline constexpr size_t kMaxLocalProbes = 64;
// Distance (metres) added in quadrature in the Shepard weights: a vertex on a probe's origin
// does not take that probe alone (each probe's texels carry their own noise).
inline constexpr float kLocalSmoothing = 0.05f;
// A probe is on the support surface's plane when its normal is within this angle of the
// surface's (the probes' own "one surface" tolerance, docs/probes-estimator.md) and its origin, 1 cm off
// its surface, within this distance of the plane (the offset plus tessellation and depth error).
inline constexpr float kSupportNormalDegrees = 25.0f;
inline constexpr float kSupportPlaneMetres = 0.03f;

// The support surface a local blend may be restricted to (ProbeField::use_neighbourhood).
struct SupportPlane {
  const Image* normals = nullptr;  // probe_normal.exr; null: no restriction
  glm::vec3 normal{0.0f, 1.0f, 0.0f};
};

// The mean of every valid probe's texels, weighted by solid angle (the constant baseline).
// phyir::Error where no probe is valid.
glm::vec3 mean_probe_radiance(const view::ProbeMosaic& probes);

class ProbeField : public render::PositionalRadiance {
 public:
  // `camera`: the panorama's centre. The mosaic must hold at least one valid probe.
  ProbeField(std::shared_ptr<const view::ProbeMosaic> probes, const glm::vec3& camera);
  // A copy of `probes` (tens of megabytes on a view's grid): for tests and one-off callers.
  ProbeField(const view::ProbeMosaic& probes, const glm::vec3& camera)
      : ProbeField(std::make_shared<const view::ProbeMosaic>(probes), camera) {}

  glm::vec3 radiance(const glm::vec3& position, const glm::vec3& direction) const override;
  // Probe (i, j)'s radiance from `direction` (its texel, piecewise constant).
  glm::vec3 probe_radiance(int i, int j, const glm::vec3& direction) const;
  // The grid cell (i, j) a world point projects to (the probe nearest it on the grid).
  glm::ivec2 cell_of(const glm::vec3& position) const;
  // The probe (row i, column j) used where cell (i, j) and its neighbours are all invalid.
  glm::ivec2 nearest_valid(int i, int j) const;
  // Local mode: only the valid probes whose origins (`positions`: probe_position.exr) lie within
  // `radius` of `centre` (at most kMaxLocalProbes, the nearest), blended by inverse squared
  // distance to the path vertex (Shepard): probes near the object light it, not those of the
  // surfaces behind it along the camera ray. Each weight is also tapered by the probe's distance
  // to `centre`, (1 - (d / reach)^2)^2, zero where the set ends (`radius`, or the nearest probe
  // left out by the cap), so that the blend changes continuously as the centre moves (dynamic
  // insertion). False (projection mode kept) when none is in reach.
  // `support`, when given, keeps only the probes on the support surface's own plane (their
  // normals, probe_normal.exr, within kSupportNormalDegrees of its normal, their origins within
  // kSupportPlaneMetres of its plane).
  bool use_neighbourhood(const Image& positions, const glm::vec3& centre, float radius,
                         const SupportPlane& support = {});
  size_t local_probe_count() const { return local_.size(); }
  // The local blend's weights are 1 / (|vertex - origin|^2 + kLocalSmoothing^2)^(power / 2).
  // Probes spread over a surface: with power 2 every ring of distance carries about the same
  // total weight (ring area ~ r dr against 1 / r^2), so the blend is a wide average over the
  // whole radius; above 2 the nearest probes dominate (docs/insert.md). Must be positive.
  void set_blend_power(float power);
  // Measure the blend's distances in the plane with this unit normal (the support surface's):
  // the vertex's foot point against the probes' (docs/insert.md: every probe sits 1 cm above
  // the surface, so a vertex's height above it is a parallax all of them share, and must not
  // make the nearest probe under the vertex count no more than one 0.5 m away).
  void set_blend_plane(const glm::vec3& normal);
  // Measure the blend's distance, for direction d, from each probe's origin to the line through
  // the vertex along d (docs/insert.md "ray distance"): radiance is constant along a ray in free
  // space, so a probe on that line sees what the vertex sees in d, and one off it sees a source
  // at distance D shifted by about (its distance to the line) / D radians. The weights then
  // depend on the direction: a small bright source (a lamp's panel, the sun) keeps its size
  // instead of being smeared over the shifted copies of every probe.
  void set_ray_distance(bool on) { ray_distance_ = on; }
  // With ray distances: the support surface's plane (a point and the unit normal on the object's
  // side). A probe below it by more than kSupportPlaneMetres is used only for the directions
  // whose ray from the vertex goes towards it ((origin - vertex) . d > 0): one behind the vertex
  // would see the vertex's direction through the support surface (the floor under a table, for
  // the table-top object's upward rays). Without it every probe is used in every direction.
  void set_support_plane(const glm::vec3& point, const glm::vec3& normal);
  // Local mode: the taper-weighted mean of the local probes' images (res_width x res_height):
  // a map that is bright wherever any blended probe sees light, for the environment's
  // importance sampling (its density only; the radiance stays the blend's). Empty otherwise.
  Image local_sampling_map() const;

 private:
  std::shared_ptr<const view::ProbeMosaic> mosaic_;  // shared with the view's cache
  const view::ProbeMosaic& probes_;
  glm::vec3 camera_;
  std::vector<glm::ivec2> fallback_;  // per cell, the valid probe nearest it
  struct LocalProbe {
    glm::ivec2 cell;
    glm::vec3 position;
    float taper = 1.0f;  // (1 - (d / reach)^2)^2 of its distance d to the centre (use_neighbourhood)
  };
  std::vector<LocalProbe> local_;  // local mode's probes (empty: projection mode)
  float blend_power_ = 2.0f;
  glm::vec3 blend_plane_{0.0f};  // zero: distances in 3D
  bool ray_distance_ = false;
  glm::vec3 support_point_{0.0f}, support_normal_{0.0f};  // zero normal: no support plane
  glm::vec3 projected_radiance(const glm::vec3& position, const glm::vec3& direction) const;
  // The texel (column, row) of `direction` in every probe, and probe (i, j)'s radiance there.
  glm::ivec2 texel_of(const glm::vec3& direction) const;
  glm::vec3 texel_radiance(int i, int j, const glm::ivec2& texel) const;
  // Whether a probe below the support plane lies behind the vertex along `direction`.
  bool sees_through_support(const glm::vec3& probe, const glm::vec3& vertex, const glm::vec3& direction) const;
};

}  // namespace phyir::insert
