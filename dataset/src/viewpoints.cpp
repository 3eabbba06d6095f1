#include "phyir/dataset/viewpoints.h"

#include <cmath>
#include <limits>

#include "phyir/core/error.h"
#include "phyir/core/log.h"
#include "phyir/core/pcg32.h"
#include "phyir/core/safe_math.h"
#include "phyir/dataset/checksum.h"

namespace phyir::dataset {

namespace {

// Two scene-provided viewpoints closer than this are one.
constexpr float kDuplicateDistance = 1e-3f;

// PCG32 stream id of viewpoint sampling (any constant; streams keep uses apart).
constexpr uint64_t kViewpointStream = 0x76696577ull;  // "view"

glm::vec3 fibonacci_direction(int i, int n) {
  const float golden_angle = kPi * (3.0f - std::sqrt(5.0f));
  const float y = 1.0f - (2.0f * float(i) + 1.0f) / float(n);
  const float r = safe_sqrt(1.0f - y * y);
  const float phi = golden_angle * float(i);
  return {r * std::cos(phi), y, r * std::sin(phi)};
}

float round_to_mm(float x) { return std::round(x * 1000.0f) / 1000.0f; }

float min_distance(const glm::vec3& p, const std::vector<Viewpoint>& others) {
  float d = std::numeric_limits<float>::infinity();
  for (const Viewpoint& v : others) d = std::min(d, glm::distance(p, v.position));
  return d;
}

}  // namespace

const char* viewpoint_source_name(ViewpointSource source) {
  switch (source) {
    case ViewpointSource::Camera: return "camera";
    case ViewpointSource::Candidate: return "candidate";
    case ViewpointSource::Sampled: return "sampled";
  }
  return "?";
}

nlohmann::json Viewpoint::to_json() const {
  return {{"source", viewpoint_source_name(source)},
          {"source_index", source_index},
          {"position", {position.x, position.y, position.z}},
          {"clearance_m", std::isfinite(clearance) ? nlohmann::json(clearance) : nlohmann::json(nullptr)}};
}

ClearanceProbe probe_clearance(const scenes::Scene& scene, const render::Accelerator& accelerator,
                               const glm::vec3& p, int rays) {
  ClearanceProbe probe;
  probe.rays = rays;
  probe.nearest = std::numeric_limits<float>::infinity();
  for (int i = 0; i < rays; ++i) {
    render::Ray ray;
    ray.origin = p;
    ray.direction = fibonacci_direction(i, rays);
    render::Hit hit;
    if (!accelerator.intersect(ray, &hit, render::Coverage::kBlendSolid)) {
      ++probe.misses;
      continue;
    }
    probe.nearest = std::min(probe.nearest, hit.t);
    const scenes::Mesh& mesh = scene.meshes[hit.mesh];
    if (scene.materials[mesh.material].double_sided) continue;
    const glm::uvec3 t = mesh.triangles[hit.triangle];
    const glm::vec3 ng = glm::cross(mesh.positions[t.y] - mesh.positions[t.x], mesh.positions[t.z] - mesh.positions[t.x]);
    if (glm::dot(ng, ray.direction) > 0.0f) ++probe.back_faces;  // arrived behind the wound side
  }
  return probe;
}

bool is_free_viewpoint(const scenes::Scene& scene, const render::Accelerator& accelerator, const glm::vec3& p,
                       const ViewpointRules& rules, ClearanceProbe* out) {
  const scenes::Bounds& b = scene.bounds;
  if (b.empty()) return false;
  const float height = p.y - b.min.y;
  if (height < rules.min_height || height > rules.max_height) return false;
  if (p.x < b.min.x || p.x > b.max.x || p.z < b.min.z || p.z > b.max.z) return false;
  const ClearanceProbe probe = probe_clearance(scene, accelerator, p, rules.clearance_rays);
  if (out) *out = probe;
  return probe.back_faces == 0 && 2 * probe.misses <= probe.rays && probe.nearest >= rules.clearance;
}

std::vector<Viewpoint> plan_viewpoints(const scenes::Scene& scene, const std::string& scene_name, int count,
                                       uint64_t seed, const ViewpointRules& rules) {
  std::vector<Viewpoint> views;
  const auto add_authored = [&](const glm::vec3& p, ViewpointSource source, int index) {
    if (int(views.size()) >= count || !is_finite(p)) return;
    if (min_distance(p, views) < kDuplicateDistance) return;
    views.push_back({p, source, index, 0.0f});
  };
  for (size_t i = 0; i < scene.cameras.size(); ++i) add_authored(scene.cameras[i].position, ViewpointSource::Camera, int(i));
  for (size_t i = 0; i < scene.candidate_viewpoints.size(); ++i)
    add_authored(scene.candidate_viewpoints[i], ViewpointSource::Candidate, int(i));

  const render::Accelerator accelerator(scene);
  // Authored viewpoints are kept as they are, but their clearance is measured and recorded.
  for (Viewpoint& v : views) {
    const ClearanceProbe probe = probe_clearance(scene, accelerator, v.position, rules.clearance_rays);
    v.clearance = probe.nearest;
    if (probe.nearest < rules.clearance || probe.back_faces > 0)
      spdlog::warn("{}: {} viewpoint {} at ({:.3f}, {:.3f}, {:.3f}) has {:.3f} m clearance and {} back-face hits "
                   "(kept: the scene names it)",
                   scene_name, viewpoint_source_name(v.source), v.source_index, v.position.x, v.position.y,
                   v.position.z, probe.nearest, probe.back_faces);
  }
  if (int(views.size()) >= count) return views;

  const scenes::Bounds& b = scene.bounds;
  if (b.empty()) fail("{}: the scene is empty; no viewpoint can be sampled", scene_name);
  // The toolkit's PCG32, seeded from SHA-256 of (seed, scene name): the same on every platform.
  Pcg32 rng(hash64(fmt::format("phyir-dataset viewpoints|{}|{}", seed, scene_name)), kViewpointStream);
  const glm::vec3 lo(b.min.x + rules.clearance, b.min.y + rules.min_height, b.min.z + rules.clearance);
  const glm::vec3 hi(b.max.x - rules.clearance, b.min.y + rules.max_height, b.max.z - rules.clearance);
  if (lo.x > hi.x || lo.z > hi.z)
    fail("{}: the scene's bounds ({:.2f} x {:.2f} m) leave no room for a {:.2f} m clearance", scene_name,
         b.max.x - b.min.x, b.max.z - b.min.z, rules.clearance);
  while (int(views.size()) < count) {
    bool found = false;
    for (int attempt = 0; attempt < rules.attempts && !found; ++attempt) {
      // Three draws per attempt whatever happens, so each attempt's point is fixed.
      const float ux = rng.next_float();  // separate statements: argument order is unspecified
      const float uy = rng.next_float();
      const float uz = rng.next_float();
      const glm::vec3 p(round_to_mm(lo.x + (hi.x - lo.x) * ux), round_to_mm(lo.y + (hi.y - lo.y) * uy),
                        round_to_mm(lo.z + (hi.z - lo.z) * uz));
      const float spacing = attempt < rules.attempts / 2 ? rules.min_spacing : 0.5f * rules.min_spacing;
      if (min_distance(p, views) < std::max(spacing, kDuplicateDistance)) continue;
      ClearanceProbe probe;
      if (!is_free_viewpoint(scene, accelerator, p, rules, &probe)) continue;
      views.push_back({p, ViewpointSource::Sampled, attempt, probe.nearest});
      found = true;
    }
    if (!found)
      fail("{}: found only {} of {} viewpoints ({} from the scene, the rest in free space with {:.2f} m clearance at "
           "{:.1f}-{:.1f} m height, {} attempts); lower the views per scene or the clearance",
           scene_name, views.size(), count, scene.cameras.size() + scene.candidate_viewpoints.size(), rules.clearance,
           rules.min_height, rules.max_height, rules.attempts);
  }
  return views;
}

}  // namespace phyir::dataset
