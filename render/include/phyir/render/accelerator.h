#pragma once
// Every ray of the toolkit goes through this interface, implemented with Embree 3.
// Geometry id = index in Scene::meshes, primitive id = triangle index. Thread-safe for
// concurrent queries after construction. Embree errors go to the logger and become
// phyir::Error.
//
// Meshes without triangles, or with non-finite positions or out-of-range indices, are
// skipped with a warning (their ids stay unused). Degenerate triangles are ignored by
// Embree. Meshes whose material is alphaMode MASK or BLEND get a coverage filter, for both
// intersect() and occluded(): MASK drops hits with alpha < cutoff, BLEND keeps a hit with
// probability alpha (as Coverage says); the filter reads the scene's textures, so the scene
// must outlive the accelerator. Opaque meshes have no filter.
#include <cstdint>
#include <memory>

#include "phyir/render/ray.h"
#include "phyir/scenes/scene.h"

namespace phyir::render {

// How a query treats alphaMode BLEND surfaces (MASK always keeps its cutoff).
enum class Coverage {
  kStochastic,   // light transport: a hit is kept with probability alpha (docs/brdf.md)
  kBlendSolid,   // geometry (AOVs, viewpoints): a blended surface is where it is
  kBlendAbsent,  // where light can get out (enclosed emitters): a blended surface lets it
};

class Accelerator {
 public:
  explicit Accelerator(const scenes::Scene& scene);
  ~Accelerator();
  Accelerator(const Accelerator&) = delete;
  Accelerator& operator=(const Accelerator&) = delete;

  // Closest hit in (tmin, tmax); false on a miss.
  bool intersect(const Ray& ray, Hit* hit, Coverage coverage = Coverage::kStochastic) const;
  // Any hit in (tmin, tmax).
  bool occluded(const Ray& ray, Coverage coverage = Coverage::kStochastic) const;
  // The fraction of light that gets through (tmin, tmax): 0 at an opaque (or MASK-kept)
  // hit, else the product of 1 - alpha over the blended surfaces crossed (Cycles'
  // transparent shadows; docs/brdf.md). Without blended surfaces, 0 or 1 as occluded().
  float transmittance(const Ray& ray) const;

  // Raw-throughput path for benchmarks: closest-hit distances of a batch (16-wide
  // packets where possible); t = +inf on a miss.
  void intersect_batch(const Ray* rays, size_t count, float* t_out) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace phyir::render
