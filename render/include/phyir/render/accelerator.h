#pragma once
// Every ray of the toolkit goes through this interface, implemented with Embree 3.
// Geometry id = index in Scene::meshes, primitive id = triangle index. Thread-safe for
// concurrent queries after construction. Embree errors go to the logger and become
// phyir::Error.
//
// Meshes without triangles, or with non-finite positions or out-of-range indices, are
// skipped with a warning (their ids stay unused). Degenerate triangles are ignored by
// Embree. Meshes whose material is alphaMode MASK get an intersection filter that drops
// hits with alpha < cutoff, for both intersect() and occluded(); the filter reads the
// scene's textures, so the scene must outlive the accelerator.
#include <cstdint>
#include <memory>

#include "phyir/render/ray.h"
#include "phyir/scenes/scene.h"

namespace phyir::render {

class Accelerator {
 public:
  explicit Accelerator(const scenes::Scene& scene);
  ~Accelerator();
  Accelerator(const Accelerator&) = delete;
  Accelerator& operator=(const Accelerator&) = delete;

  // Closest hit in (tmin, tmax); false on a miss.
  bool intersect(const Ray& ray, Hit* hit) const;
  // Any hit in (tmin, tmax).
  bool occluded(const Ray& ray) const;

  // Raw-throughput path for benchmarks: closest-hit distances of a batch (16-wide
  // packets where possible); t = +inf on a miss.
  void intersect_batch(const Ray* rays, size_t count, float* t_out) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace phyir::render
