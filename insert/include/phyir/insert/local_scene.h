#pragma once
// The local scene of differential rendering (Debevec 1998; the paper's D.2): the object, placed
// standing on a surface point of the view, and a disc of that surface's material under it that
// catches its shadow and inter-reflection. Everything else comes from the lighting.
#include <glm/glm.hpp>

#include "phyir/insert/insert_view.h"
#include "phyir/scenes/scene.h"

namespace phyir::insert {

struct Placement {
  float scale = 1.0f;  // uniform, applied to the object as loaded (metres)
  float yaw = 0.0f;    // radians about +Y
};

// The support disc's radius: this many times the placed object's horizontal half-extent
// (its shadow under light from above reaches about that far), at least kMinDiscRadius.
inline constexpr float kDiscRadiusFactor = 3.0f;
inline constexpr float kMinDiscRadius = 0.05f;

// The object's triangles moved so that its bounding box's bottom centre stands on
// `ground.position` (lifted along +Y by 0.5 mm so it rests on, not inside, the disc), scaled and
// turned about +Y. Materials and textures come along; lights, cameras and the environment do not.
scenes::Scene place_object(const scenes::Scene& object, const SurfacePoint& ground, const Placement& placement);

// A flat disc centred on `ground.position`, facing `ground.normal`, with the view's base
// colour, roughness and metalness there.
scenes::Scene support_disc(const SurfacePoint& ground, float radius);

// `a` and `b` in one scene (b's material and texture indices shifted).
scenes::Scene merge_scenes(const scenes::Scene& a, const scenes::Scene& b);

// The disc radius for a placed object.
float disc_radius_for(const scenes::Scene& placed, const SurfacePoint& ground);

}  // namespace phyir::insert
