#pragma once
// Where per-pixel light probes sit and how they are laid out (the SC lighting label of the
// PhyIR paper, sec. 3.2 and C.1: a 16x32 probe per pixel of a 128x256 grid of a 256x512
// panorama). docs/probes.md is the user-facing description.
//
// Layout: view/probe_layout.h (a grid of H x W probes, each an h x w equirectangular image,
// probe (i, j) the block of rows [i h, (i+1) h) and columns [j w, (j+1) w) of the mosaic).
//
// Placement. Probe (i, j) belongs to the direction through the centre of grid cell (i, j),
// i.e. the camera's continuous pixel position ((j + 0.5) width / W, (i + 0.5) height / H).
// For a grid of half the panorama's resolution that is the corner shared by the 2x2 block of
// pixels (2i, 2j) .. (2i+1, 2j+1); for a grid of the panorama's resolution it is the pixel
// centre (the same ray as the AOVs). The probe's origin is the first surface seen along that
// ray, moved off it along its shading normal (the side facing the camera) by the offset.
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

// The camera's continuous pixel position of probe (i, j) (see the layout note above).
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

// The same directions with the texel's row-edge cosines computed once, for loops that ask
// for many directions of one texel (and no inverse trigonometry per direction).
class ProbeTexel {
 public:
  ProbeTexel(int row, int col, int height, int width);
  glm::vec3 direction(const glm::vec2& a) const;

 private:
  double cos0_, cos1_;
  float col_, width_;
};

// `count` points of [0,1)^2 stratified on the smallest s x t grid with s t >= count
// (s = ceil(sqrt(count))): distinct cells picked by a random permutation, one jittered point
// in each. Every point is uniform over the square on its own, so any average over them is
// unbiased; when count is a perfect square every cell is used once.
//
// Interleaving (count n > 1): each cell is split n x n and the point is jittered inside
// sub-cell (sub + shift(cell)) mod n, shift a hash of (key, cell). Calls with one key and all
// n^2 values of `sub` cover every sub-cell of every cell they pick once; each call alone is
// still stratified and unbiased (the shift is uniform over the sub-cells).
struct Interleave {
  glm::ivec2 sub{0};  // column, row in [0, count)
  int count = 1;
  uint64_t key = 0;
};
void stratified_square(int count, Rng& rng, std::vector<glm::vec2>* points, const Interleave& interleave = {});

// The variance of the mean of `values`, drawn one at each of stratified_square's `points`
// (same order), from the differences between cells 2k and 2k+1 of each row of its grid
// (collapsed strata). A pair's squared difference estimates the two cells' variances plus
// the difference of their means, so in expectation the estimate errs high, by the light's
// variation across one cell; the samples' spread would count all of it across the square,
// which stratification resolves (an edge through a texel). Negative where fewer than
// `min_pairs` pairs of cells both hold a point.
double stratified_mean_variance(const std::vector<glm::vec2>& points, const std::vector<float>& values, int min_pairs);

}  // namespace phyir::render
