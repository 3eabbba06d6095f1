#pragma once
// The one equirectangular mapping of the toolkit (panoramas, probes, environment maps, the
// analytic sky, the network's warp and the evaluation all use it). Blender's convention, so
// outputs line up with Cycles renders of the same glTF:
//   row 0 looks straight up (+Y); the centre column looks along -Z;
//   for a unit direction d:  u = 0.5 + atan2(d.x, -d.z) / (2 pi),  v = acos(d.y) / pi;
//   pixel (i, j) (column i, row j) of a W x H image has its centre at
//   u = (i + 0.5) / W, v = (j + 0.5) / H.
// So u grows towards +X from the centre (-Z); u = 0 and u = 1 look along +Z.
// In core so that scene generation (the sky) and rendering share it; render/equirect.h
// names the same functions in phyir::render.
#include <glm/glm.hpp>

namespace phyir {

// (u, v) in [0,1]^2 to a unit world direction.
glm::vec3 equirect_direction(glm::vec2 uv);

// The same at column coordinate u, with the polar angle given by its cosine and sine (for
// callers that have them without theta: no inverse trigonometry).
glm::vec3 equirect_direction(float u, float cos_theta, float sin_theta);

// Unit direction to (u, v) in [0,1]^2 (u in [0,1), v in [0,1]).
glm::vec2 equirect_uv(const glm::vec3& direction);

// Solid angle of the texel in row j of an H-row equirectangular image of width W:
// (2 pi / W) * (cos(theta_top) - cos(theta_bottom)). Exact, so rows sum to 4 pi.
float equirect_texel_solid_angle(int row, int width, int height);

// The density, per steradian, of a direction picked uniformly in (u, v):
// 1 / (2 pi^2 sin(theta)).  Returns 0 at the poles where sin(theta) = 0.
float equirect_uv_pdf_to_solid_angle(float sin_theta);

}  // namespace phyir
