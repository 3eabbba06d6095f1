#include "phyir/render/gbuffer.h"

namespace phyir::render {

GBufferSample GBufferSample::from_hit(const SurfaceInteraction& si) {
  GBufferSample g;
  g.depth = si.distance;
  g.normal = si.shading_normal;
  g.basecolor = si.brdf.base_color;
  g.roughness = si.brdf.roughness;
  g.metalness = si.brdf.metalness;
  g.emissive = si.emits ? 1.0f : 0.0f;
  g.transparent = (si.transmission > 0.0f || si.opacity < 1.0f) ? 1.0f : 0.0f;
  g.geometry = 1.0f;
  return g;
}

}  // namespace phyir::render
