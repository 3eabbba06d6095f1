#pragma once
// Where per-pixel light probes sit and how their texels are sampled (the PhyIR paper's SC
// lighting label, sec. 3.2 and C.1; docs/probes.md, "What a probe is" and "Which pixel a probe
// belongs to"). Layout: H x W probes of h x w texels, view/probe_layout.h.
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "phyir/render/camera.h"
#include "phyir/render/render_scene.h"
#include "phyir/render/rng.h"
#include "phyir/view/probe_layout.h"

namespace phyir::render {

// The grid's layout in probes.exr: the view folder's (view/probe_layout.h).
using ProbeLayout = view::ProbeLayout;

// Why a probe is or is not a valid label. The mask is 1 only for kValid, matching the paper's
// M_mask ("object regions except light source and transmission object", eq. 7).
enum class ProbeStatus : uint8_t {
  kValid = 0,
  kNothing = 1,      // the ray sees no surface: probe, position and mask are 0
  kEmitter = 2,      // the surface emits towards the camera: probe computed, mask 0
  kTransparent = 3,  // glass or alpha below 1: probe computed, mask 0
};

struct ProbeSite {
  glm::vec3 surface{0.0f};  // first surface along the placement ray
  glm::vec3 normal{0.0f};   // its unit shading normal, facing the camera (as normal.exr)
  glm::vec3 origin{0.0f};   // surface + offset * normal: where the probe sees from
  float offset = 0.0f;      // the offset used (shortened if something is closer, see place_probes)
  ProbeStatus status = ProbeStatus::kNothing;

  bool computed() const { return status != ProbeStatus::kNothing; }
  bool valid() const { return status == ProbeStatus::kValid; }
};

// The camera's continuous pixel position of probe (i, j): ((j + 0.5) width / W, (i + 0.5) height / H).
glm::vec2 probe_pixel_position(const ProbeLayout& layout, const CameraModel& camera, int i, int j);

// One site per probe, row-major (index i * W + j), from one ray each (no random numbers).
// `offset` is in metres along the shading normal; if a surface lies closer than that along
// the normal (a gap narrower than the offset), the origin is put half way to it instead.
std::vector<ProbeSite> place_probes(const RenderScene& scene, const CameraModel& camera,
                                    const ProbeLayout& layout, float offset);

// A direction inside texel (row, col) of an h x w probe, uniform in solid angle over the
// texel for `a` uniform in [0,1)^2: phi uniform across the texel's columns, cos(theta)
// uniform between its rows' edges, then equirect_direction() of the result.
glm::vec3 probe_texel_direction(int row, int col, int height, int width, const glm::vec2& a);

// probe_texel_direction() with the row-edge cosines computed once, for many directions of one texel.
class ProbeTexel {
 public:
  ProbeTexel(int row, int col, int height, int width);
  glm::vec3 direction(const glm::vec2& a) const;

 private:
  double cos0_, cos1_;
  float col_, width_;
};

// `count` points of [0,1)^2, one jittered point in each of `count` distinct cells (random
// permutation) of the s x t grid, s = ceil(sqrt(count)), t = ceil(count / s). Each point is
// uniform on its own, so any average is unbiased.
// Interleaving (count n > 1): the point is jittered in sub-cell (sub + shift) mod n of its
// cell's n x n, shift a hash of (key, cell): calls with one key and all n^2 `sub` cover each
// picked cell's sub-cells once; each call alone stays stratified and unbiased.
struct Interleave {
  glm::ivec2 sub{0};  // column, row in [0, count)
  int count = 1;
  uint64_t key = 0;
};
void stratified_square(int count, Rng& rng, std::vector<glm::vec2>* points, const Interleave& interleave = {});

// The variance of the mean of `values` (one per stratified_square point, same order) from
// the differences between cells 2k and 2k+1 of each grid row (collapsed strata): errs high by
// the light's variation across one cell, but does not count an edge the strata resolve, as
// the samples' spread would. Negative where fewer than `min_pairs` pairs hold both points.
double stratified_mean_variance(const std::vector<glm::vec2>& points, const std::vector<float>& values, int min_pairs);

}  // namespace phyir::render
