#pragma once
// Where a scene's views are taken from: the scene's camera nodes first, then the candidate
// viewpoints of its extras (both trusted as authored, in file order, duplicates within 1 mm
// dropped), then points sampled in free space until there are enough.
//
// A sampled point lies inside the scene's bounds, min_height..max_height above the floor
// (the scene's lowest point), on a millimetre grid, and passes the clearance test: rays in
// `clearance_rays` directions (a Fibonacci sphere) all hit a surface's front face (or a
// double-sided material) no closer than `clearance` metres; at most half of them may miss
// (open scenes). A back-face hit means the point is inside a solid or outside a wall (the
// notch of an L-shaped room), so it is rejected. Points also keep `min_spacing` from every
// other viewpoint (halved after half the attempts). Draws come from the toolkit PCG32 keyed by
// (seed, scene name), so the plan is deterministic, and the first k of a longer plan are a
// plan of k.
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include "phyir/dataset/settings.h"
#include "phyir/render/accelerator.h"
#include "phyir/scenes/scene.h"

namespace phyir::dataset {

enum class ViewpointSource { Camera, Candidate, Sampled };
const char* viewpoint_source_name(ViewpointSource source);  // "camera", "candidate", "sampled"

struct Viewpoint {
  glm::vec3 position{0.0f};
  ViewpointSource source = ViewpointSource::Sampled;
  int source_index = 0;  // camera or candidate index; for sampled, the attempt that found it
  float clearance = 0.0f;  // nearest surface seen by the clearance rays, metres

  nlohmann::json to_json() const;
};

struct ClearanceProbe {
  float nearest = 0.0f;  // closest hit over all rays (infinity when every ray misses)
  int back_faces = 0;    // rays whose first hit is the back of a one-sided surface
  int misses = 0;
  int rays = 0;
};

// Casts `rays` rays from p (Fibonacci sphere directions) against the scene.
ClearanceProbe probe_clearance(const scenes::Scene& scene, const render::Accelerator& accelerator,
                               const glm::vec3& p, int rays);

// The sampled-viewpoint test of the header comment (height and bounds included).
bool is_free_viewpoint(const scenes::Scene& scene, const render::Accelerator& accelerator,
                       const glm::vec3& p, const ViewpointRules& rules, ClearanceProbe* probe = nullptr);

// `count` viewpoints for `scene`. `scene_name` keys the random stream. Throws phyir::Error
// naming the scene when free space yields too few.
std::vector<Viewpoint> plan_viewpoints(const scenes::Scene& scene, const std::string& scene_name, int count,
                                       uint64_t seed, const ViewpointRules& rules);

}  // namespace phyir::dataset
