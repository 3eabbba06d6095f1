// EmitterSampler's light-side sampling (emitter_sampler.h): where light subpaths from the
// emissive triangles start (light_subpaths.h, docs/light-subpaths.md).
#include "phyir/render/emitter_sampler.h"

#include "phyir/core/safe_math.h"
#include "phyir/render/material_eval.h"
#include "phyir/render/sampling.h"

namespace phyir::render {

namespace {

// The probability of each side of a double-sided emitter.
constexpr float kSideProbability = 0.5f;

}  // namespace

float EmitterSampler::emission_pmf(const glm::vec3& choice_from, int index) const {
  if (!spatial_) return distribution_.pmf(index);
  float total = 0.0f;
  const float* weights = selection_weights_at(choice_from, false, &total);
  const EmissiveTriangle& e = triangles_[size_t(index)];
  return total > 0.0f ? weights[e.cluster] / total * e.pmf_in_cluster : 0.0f;
}

float EmitterSampler::emission_density(const glm::vec3& choice_from, int mesh, int triangle) const {
  const int index = index_of(mesh, triangle);
  if (index < 0) return 0.0f;
  const EmissiveTriangle& e = triangles_[size_t(index)];
  const bool two_sided = scene_->materials[size_t(scene_->meshes[size_t(e.mesh)].material)].double_sided;
  return safe_div(emission_pmf(choice_from, index), e.area) * (two_sided ? kSideProbability : 1.0f);
}

bool EmitterSampler::sample_emission(const glm::vec3& choice_from, const EmissionVariates& u, EmissionSample* out) const {
  if (triangles_.empty()) return false;
  int index = -1;
  if (spatial_) {
    int entry;
    float entry_pmf, remapped;
    if (!choose_spatially(choice_from, u.select, false, &entry, &entry_pmf, &remapped)) return false;
    const Cluster& c = clusters_[size_t(entry)];
    const int k = c.distribution.sample(remapped);
    if (k < 0) return false;
    index = c.triangles[size_t(k)];
  } else {
    index = distribution_.sample(u.select);
  }
  if (index < 0) return false;
  const EmissiveTriangle& e = triangles_[size_t(index)];
  const scenes::Mesh& mesh = scene_->meshes[size_t(e.mesh)];
  const scenes::Material& material = scene_->materials[size_t(mesh.material)];
  const glm::vec3 bary = barycentrics(sample_uniform_triangle(u.point));
  out->position = e.p0 * bary.x + e.p1 * bary.y + e.p2 * bary.z;
  out->normal = material.double_sided && u.side < kSideProbability ? -e.normal : e.normal;
  out->mesh = e.mesh;
  out->triangle = e.triangle;
  out->density = safe_div(emission_pmf(choice_from, index), e.area) * (material.double_sided ? kSideProbability : 1.0f);
  const glm::uvec3 tri = mesh.triangles[size_t(e.triangle)];
  out->radiance = coverage_at(*scene_, mesh, material, tri, bary) * emitted_radiance(*scene_, mesh, material, tri, bary);
  return out->density > 0.0f && max_component(out->radiance) > 0.0f;
}

}  // namespace phyir::render
