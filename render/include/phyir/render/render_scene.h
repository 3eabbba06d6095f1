#pragma once
// The scene as the integrator sees it: geometry in Embree, materials ready to evaluate
// at a hit, the emitter sampler and the optional environment.
#include <memory>

#include "phyir/render/accelerator.h"
#include "phyir/render/emitter_sampler.h"
#include "phyir/render/environment_light.h"
#include "phyir/render/environment_portals.h"
#include "phyir/render/interaction.h"
#include "phyir/render/ray.h"
#include "phyir/scenes/scene.h"

namespace phyir::render {

class RenderScene {
 public:
  // `environment` may be null. The scene must outlive this object.
  RenderScene(const scenes::Scene& scene, std::unique_ptr<EnvironmentLight> environment = nullptr);

  const scenes::Scene& scene() const { return *scene_; }
  const Accelerator& accelerator() const { return accelerator_; }
  const EmitterSampler& emitters() const { return emitters_; }
  const EnvironmentLight* environment() const { return environment_.get(); }
  // The scene's light portals (scenes::Portal), where it has an environment; else empty.
  const EnvironmentPortals& portals() const { return portals_; }

  // Interpolates attributes and evaluates the material (textures, factors, alpha,
  // normal map) at `hit` of `ray`. Never produces NaN: degenerate triangles fall back to
  // any finite normal.
  SurfaceInteraction interact(const Ray& ray, const Hit& hit) const;

  // Closest surface along the ray; false on a miss. Light transport keeps a blended
  // surface with probability alpha; the AOVs ask for Coverage::kBlendSolid.
  bool trace(const Ray& ray, SurfaceInteraction* si, Coverage coverage = Coverage::kStochastic) const;

  // Only the emission of the closest surface (zero if it does not emit) and its distance;
  // false on a miss. The same values as trace(), without evaluating a surface that cannot
  // emit (for rays that only look for lights).
  bool trace_emission(const Ray& ray, glm::vec3* emission, float* distance) const;

 private:
  const scenes::Scene* scene_;
  Accelerator accelerator_;
  EmitterSampler emitters_;
  std::unique_ptr<EnvironmentLight> environment_;
  EnvironmentPortals portals_;
};

}  // namespace phyir::render
