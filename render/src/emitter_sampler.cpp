#include "phyir/render/emitter_sampler.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>

#include "phyir/core/safe_math.h"
#include "phyir/render/emitter_visibility.h"
#include "phyir/render/light_triangles.h"
#include "phyir/render/material_eval.h"
#include "phyir/render/spherical_triangle.h"

namespace phyir::render {

namespace {

std::atomic<uint64_t> next_sampler_id{1};

// One thread's last selection weights (EmitterSampler::selection_weights_at).
struct SelectionMemo {
  uint64_t sampler = 0;  // no sampler has id 0
  glm::vec3 reference{0.0f};
  float total = 0.0f;           // of every entry
  float triangle_total = 0.0f;  // of the clusters alone
  // Every member initialised: the thread_local is constant-initialised, no guard per call.
  float weights[EmitterSampler::kMaxSpatialClusters] = {};
};

struct Geometry {
  glm::vec3 wi{0.0f};
  float distance = 0.0f;
  float pdf = 0.0f;
  float cos_light = 0.0f;  // signed: > 0 when the reference sees the front face
};

// Direction, distance and cosine at the emitter of `point` seen from `reference`, with the
// solid-angle density `pdf` of having sampled it, where pdf_of(dist2, |cos|) gives it. Shared
// by sample() and pdf() so the two agree bit for bit. Grazing (|cos| < kMinCosine) and
// coincident points get density 0 in both, so multiple importance sampling stays consistent.
template <typename Density>
Geometry point_geometry(const glm::vec3& normal, const glm::vec3& reference, const glm::vec3& point, Density pdf_of) {
  Geometry g;
  const glm::vec3 d = point - reference;
  const float dist2 = glm::dot(d, d);
  if (!(dist2 > 0.0f) || !std::isfinite(dist2)) return g;
  g.distance = std::sqrt(dist2);
  g.wi = d / g.distance;
  g.cos_light = -glm::dot(normal, g.wi);
  const float abs_cos = std::abs(g.cos_light);
  if (abs_cos < kMinCosine) return g;
  g.pdf = pdf_of(dist2, abs_cos);
  if (!std::isfinite(g.pdf)) g.pdf = 0.0f;
  return g;
}

// How far from a triangle's plane a reference may lie and still be in it, per unit of its
// largest coordinate (about 128 float steps: below the ray offset of ray_offset.h, above the
// rounding of a hit point).
constexpr float kInPlaneTolerance = 1.0f / 65536.0f;

// The reference lies in the triangle's plane: on the light itself or on a coplanar neighbour,
// which it sees edge-on (no light). Its own triangle would otherwise be sampled at a distance
// of float noise, in a direction of float noise, with a weight of thousands.
bool in_plane(const glm::vec3& normal, const glm::vec3& vertex, const glm::vec3& reference) {
  const glm::vec3 a = glm::abs(reference);
  const float scale = std::max({1.0f, a.x, a.y, a.z});
  return std::abs(glm::dot(normal, reference - vertex)) <= kInPlaneTolerance * scale;
}

// A point uniform on a triangle of `area` picked with probability `pmf`: pmf / area * d^2 / |cos|.
Geometry area_sampled(float pmf, float area, const glm::vec3& normal, const glm::vec3& reference,
                      const glm::vec3& point) {
  return point_geometry(normal, reference, point,
                        [&](float dist2, float abs_cos) { return pmf * dist2 / (area * abs_cos); });
}

// A point uniform in the triangle's solid angle `omega`: pmf / omega.
Geometry solid_angle_sampled(float pmf, double omega, const glm::vec3& normal, const glm::vec3& reference,
                             const glm::vec3& point) {
  return point_geometry(normal, reference, point, [&](float, float) { return float(double(pmf) / omega); });
}

}  // namespace

// (b1, b2) of a point in the triangle's plane, clamped into the triangle.
glm::vec2 EmitterSampler::barycentrics_of(const EmissiveTriangle& e, const glm::vec3& point) {
  const glm::vec3 e1 = e.p1 - e.p0, e2 = e.p2 - e.p0, v = point - e.p0;
  const float d00 = glm::dot(e1, e1), d01 = glm::dot(e1, e2), d11 = glm::dot(e2, e2);
  const float d20 = glm::dot(v, e1), d21 = glm::dot(v, e2);
  const float denominator = d00 * d11 - d01 * d01;
  glm::vec2 b(safe_div(d11 * d20 - d01 * d21, denominator), safe_div(d00 * d21 - d01 * d20, denominator));
  b = glm::clamp(b, glm::vec2(0.0f), glm::vec2(1.0f));
  const float sum = b.x + b.y;
  return sum > 1.0f ? b / sum : b;
}

namespace {

// Half the diagonal of the scene's bounds: the radius of the disc a directional light can light.
float bounding_radius(const scenes::Scene& scene) {
  const scenes::Bounds bounds = scene.compute_bounds();
  return bounds.empty() ? 1.0f : 0.5f * glm::length(bounds.max - bounds.min);
}

}  // namespace

namespace {

// Power per unit area of an emissive material: luminance of the emission, times its
// texture's mean; 0 when it emits nothing.
float power_density_of(const scenes::Scene& scene, const scenes::Material& material) {
  float power_density = luminance(material.emission());
  const scenes::TextureSlot& slot = material.emissive_texture;
  if (slot.present() && static_cast<size_t>(slot.texture) < scene.textures.size())
    power_density *= mean_luminance(scene.textures[slot.texture]);
  return power_density > 0.0f && std::isfinite(power_density) ? power_density : 0.0f;
}

}  // namespace

bool EmitterSampler::make_triangle(const scenes::Mesh& mesh, int m, int t, EmissiveTriangle* e) {
  const glm::uvec3 tri = mesh.triangles[size_t(t)];
  const size_t n = mesh.positions.size();
  if (tri.x >= n || tri.y >= n || tri.z >= n) return false;
  *e = EmissiveTriangle{m, t, mesh.positions[tri.x], mesh.positions[tri.y], mesh.positions[tri.z], glm::vec3(0.0f),
                        0.0f, glm::vec3(0.0f), 0.0f, /*cluster=*/-1, /*slot=*/-1, /*pmf_in_cluster=*/0.0f};
  const glm::vec3 c = glm::cross(e->p1 - e->p0, e->p2 - e->p0);
  const float len = glm::length(c);
  // Zero-area (or non-finite) triangles emit nothing and cannot be sampled uniformly.
  if (!(len > 0.0f) || !std::isfinite(len) || !is_finite(e->p0) || !is_finite(e->p1) || !is_finite(e->p2))
    return false;
  e->normal = c / len;
  e->area = 0.5f * len;
  e->centroid = (e->p0 + e->p1 + e->p2) / 3.0f;
  e->longest_edge2 = std::max({glm::dot(e->p1 - e->p0, e->p1 - e->p0), glm::dot(e->p2 - e->p1, e->p2 - e->p1),
                               glm::dot(e->p0 - e->p2, e->p0 - e->p2)});
  return true;
}

EmitterSampler::EmitterSampler(const scenes::Scene& scene, const Accelerator* occluders)
    : scene_(&scene),
      delta_(scene.lights, scene.lights.empty() ? 1.0f : bounding_radius(scene)),
      id_(next_sampler_id.fetch_add(1)) {
  first_of_mesh_.assign(scene.meshes.size(), -1);
  std::vector<float> weights;
  EmitterTwins twins;
  for (size_t m = 0; m < scene.meshes.size(); ++m) {
    const scenes::Mesh& mesh = scene.meshes[m];
    if (mesh.material < 0 || static_cast<size_t>(mesh.material) >= scene.materials.size()) continue;
    const scenes::Material& material = scene.materials[mesh.material];
    if (!material.is_emissive() || mesh.triangles.empty()) continue;
    const float power_density = power_density_of(scene, material);
    if (power_density == 0.0f) continue;

    first_of_mesh_[m] = static_cast<int>(lookup_.size());
    for (size_t t = 0; t < mesh.triangles.size(); ++t) {
      lookup_.push_back(-1);
      EmissiveTriangle e;
      if (!make_triangle(mesh, int(m), int(t), &e)) continue;
      const float weight = e.area * power_density;
      if (!(weight > 0.0f) || !std::isfinite(weight)) continue;
      const scenes::TriangleCorners corners(e.p0, e.p1, e.p2);
      if (const int kept = twins.kept(corners); kept >= 0) {
        lookup_.back() = kept;  // a ray hitting this twin hit the kept triangle's sheet
        ++twins_;
        continue;
      }
      if (occluders && emits_only_into_solids(scene, *occluders, e.p0, e.p1, e.p2, e.normal, material.double_sided)) {
        ++enclosed_;
        continue;
      }
      lookup_.back() = static_cast<int>(triangles_.size());
      twins.keep(corners, lookup_.back(), material.double_sided);
      triangles_.push_back(e);
      weights.push_back(weight);
    }
  }
  build_clusters(weights);
  distribution_ = Distribution1D(std::move(weights));
  if (!delta_.empty()) {
    std::vector<float> powers;
    for (int i = 0; i < delta_.size(); ++i) powers.push_back(delta_.power(i));
    delta_distribution_ = Distribution1D(std::move(powers));
    // Power of the emissive triangles: a Lambertian face of radiance L and area A sends pi L A.
    const float triangle_power = kPi * distribution_.total();
    triangle_share_ = safe_div(triangle_power, triangle_power + delta_.total_power());
  }
  if (!triangles_.empty())
    spdlog::debug(
        "emitter sampler: {} emissive triangles in {} clusters ({}), total power {}; {} enclosed and {} twins left out",
        triangles_.size(), clusters_.size(), spatial_ ? "spatial selection" : "power selection", total_power(),
        enclosed_, twins_);
}

void EmitterSampler::build_clusters(const std::vector<float>& weights) {
  // Coplanar triangles of one mesh share a cluster; a mesh with more planes than this is
  // treated as one curved cluster (no facing test).
  constexpr size_t kMaxPlanesPerMesh = 16;
  // Two triangles are coplanar when normals agree to 1e-4 and planes to 0.1 mm.
  constexpr float kNormalTolerance = 1e-4f, kOffsetTolerance = 1e-4f;
  size_t begin = 0;
  while (begin < triangles_.size()) {
    size_t end = begin;
    while (end < triangles_.size() && triangles_[end].mesh == triangles_[begin].mesh) ++end;
    const scenes::Material& material = scene_->materials[scene_->meshes[triangles_[begin].mesh].material];
    std::vector<Cluster> planes;
    for (size_t i = begin; i < end; ++i) {
      const EmissiveTriangle& e = triangles_[i];
      const float offset = glm::dot(e.normal, e.p0);
      auto same_plane = [&](const Cluster& c) {
        return glm::dot(c.normal, e.normal) > 1.0f - kNormalTolerance && std::abs(c.plane_offset - offset) < kOffsetTolerance;
      };
      auto it = std::find_if(planes.begin(), planes.end(), same_plane);
      if (it == planes.end()) {
        if (planes.size() == kMaxPlanesPerMesh) {
          planes.clear();
          break;
        }
        Cluster c;
        c.normal = e.normal;
        c.plane_offset = offset;
        c.planar = true;
        c.one_sided_plane = !material.double_sided;
        planes.push_back(c);
        it = planes.end() - 1;
      }
      it->triangles.push_back(static_cast<int>(i));
    }
    if (planes.empty()) {  // curved: one cluster for the whole mesh
      Cluster c;
      for (size_t i = begin; i < end; ++i) c.triangles.push_back(static_cast<int>(i));
      planes.push_back(c);
    }
    for (Cluster& c : planes) {
      scenes::Bounds bounds;
      std::vector<EmitterTree::Item> items;
      std::vector<float> w;
      for (int i : c.triangles) {
        const EmissiveTriangle& e = triangles_[i];
        for (const glm::vec3& p : {e.p0, e.p1, e.p2}) bounds.extend(p);
        const glm::vec3 lo = glm::min(e.p0, glm::min(e.p1, e.p2)), hi = glm::max(e.p0, glm::max(e.p1, e.p2));
        items.push_back({lo, hi, e.area, weights[i], e.normal});
        w.push_back(weights[i]);
        c.power += weights[i];
      }
      c.centre = 0.5f * (bounds.min + bounds.max);
      c.bounds_min = bounds.min;
      c.bounds_max = bounds.max;
      c.half_diagonal2 = 0.25f * glm::dot(bounds.max - bounds.min, bounds.max - bounds.min);
      c.distribution = Distribution1D(std::move(w));
      c.tree = EmitterTree(items);
      const int cluster_index = static_cast<int>(clusters_.size());
      for (size_t k = 0; k < c.triangles.size(); ++k) {
        triangles_[c.triangles[k]].cluster = cluster_index;
        triangles_[c.triangles[k]].slot = static_cast<int>(k);
        triangles_[c.triangles[k]].pmf_in_cluster = c.distribution.pmf(static_cast<int>(k));
      }
      clusters_.push_back(std::move(c));
    }
    begin = end;
  }
  const size_t entries = clusters_.size() + size_t(delta_.size());
  spatial_ = entries <= size_t(kMaxSpatialClusters);  // one cluster too: its tree chooses inside it
}

float EmitterSampler::selection_weights(const glm::vec3& reference, float* weights, float* triangle_total) const {
  float total = 0.0f;
  for (size_t i = 0; i < clusters_.size(); ++i) {
    const Cluster& c = clusters_[i];
    float w = 0.0f;
    const float height = c.planar ? glm::dot(c.normal, reference) - c.plane_offset : 1.0f;
    // A one-sided plane lights only the half-space its front faces (cos_light > 0 there).
    if (!c.one_sided_plane || height > 0.0f) {
      const glm::vec3 d = c.centre - reference;
      // Distance to the centre, but never less than the cluster's own size: close to a
      // large panel its far parts matter as much as its centre.
      w = c.power / std::max(glm::dot(d, d), c.half_diagonal2);
      if (c.planar) {
        // cos at the emitter is height / distance, and no point of the cluster is nearer
        // than its bounding box: an upper bound that is > 0 whenever the plane can light
        // the point (e.g. a panel's edge seen along the ceiling gets almost nothing).
        const glm::vec3 nearest = glm::clamp(reference, c.bounds_min, c.bounds_max);
        const float h = std::abs(height);
        w *= h / std::max(glm::length(reference - nearest), h);
      }
    }
    weights[i] = std::isfinite(w) ? w : 0.0f;
    total += weights[i];
  }
  *triangle_total = total;
  for (int j = 0; j < delta_.size(); ++j) {
    float& w = weights[clusters_.size() + size_t(j)];
    w = delta_.weight(j, reference);
    total += w;
  }
  return total;
}

const float* EmitterSampler::selection_weights_at(const glm::vec3& reference, bool punctual, float* total) const {
  thread_local SelectionMemo memo;
  if (memo.sampler != id_ || memo.reference != reference) {
    memo.total = selection_weights(reference, memo.weights, &memo.triangle_total);
    memo.sampler = id_;
    memo.reference = reference;
  }
  *total = punctual ? memo.total : memo.triangle_total;
  return memo.weights;
}

float EmitterSampler::distance_bound(const glm::vec3& point) const {
  float nearest2 = std::numeric_limits<float>::infinity();
  for (const Cluster& c : clusters_) {
    const glm::vec3 d = point - glm::clamp(point, c.bounds_min, c.bounds_max);
    nearest2 = std::min(nearest2, glm::dot(d, d));
  }
  return std::min(std::sqrt(nearest2), delta_.distance_bound(point));
}

float EmitterSampler::selection_pmf(const glm::vec3& reference, int index, bool punctual) const {
  if (!spatial_) return distribution_.pmf(index) * (punctual ? triangle_share_ : 1.0f);
  float total = 0.0f;
  const float* weights = selection_weights_at(reference, punctual, &total);
  const EmissiveTriangle& e = triangles_[index];
  return total > 0.0f ? weights[e.cluster] / total * in_cluster_pmf(reference, e) : 0.0f;
}

bool EmitterSampler::near_cluster(const Cluster& c, const glm::vec3& reference) {
  const glm::vec3 d = glm::clamp(reference, c.bounds_min, c.bounds_max) - reference;
  return glm::dot(d, d) < 4.0f * c.half_diagonal2;
}

float EmitterSampler::in_cluster_pmf(const glm::vec3& reference, const EmissiveTriangle& e) const {
  const Cluster& c = clusters_[size_t(e.cluster)];
  if (!near_cluster(c, reference)) return e.pmf_in_cluster;
  return 0.5f * (e.pmf_in_cluster + c.tree.pmf(reference, e.slot));
}

int EmitterSampler::choose_in_cluster(const Cluster& c, const glm::vec3& reference, float u, float* pmf) const {
  *pmf = 0.0f;
  if (!near_cluster(c, reference)) {
    const int k = c.distribution.sample(u);
    if (k < 0) return -1;
    const int index = c.triangles[size_t(k)];
    *pmf = triangles_[size_t(index)].pmf_in_cluster;
    return index;
  }
  // Half the samples by the tree, half by power; the pmf is the mixture's. The tree's
  // descent gives its own pmf, bit-identical to EmitterTree::pmf.
  float tree_pmf = 0.0f;
  int k;
  if (u < 0.5f) {
    k = c.tree.sample(reference, std::min(2.0f * u, kOneMinusEpsilon), &tree_pmf);
  } else {
    k = c.distribution.sample(std::min(2.0f * u - 1.0f, kOneMinusEpsilon));
    if (k >= 0) tree_pmf = c.tree.pmf(reference, k);
  }
  if (k < 0) return -1;
  const int index = c.triangles[size_t(k)];
  *pmf = 0.5f * (triangles_[size_t(index)].pmf_in_cluster + tree_pmf);
  return index;
}

bool EmitterSampler::choose_spatially(const glm::vec3& reference, float u_select, bool punctual, int* entry,
                                      float* entry_pmf, float* remapped) const {
  float total = 0.0f;
  const float* weights = selection_weights_at(reference, punctual, &total);
  if (!(total > 0.0f)) return false;
  // Invert the cumulative weights; u_select is reused inside the chosen cluster.
  const size_t entries = clusters_.size() + (punctual ? size_t(delta_.size()) : 0);
  float target = u_select * total, acc = 0.0f;
  int chosen = -1;
  for (size_t i = 0; i < entries; ++i) {
    if (weights[i] <= 0.0f) continue;
    chosen = static_cast<int>(i);
    if (target < acc + weights[i]) break;
    acc += weights[i];
  }
  *entry = chosen;
  *entry_pmf = weights[chosen] / total;
  *remapped = std::clamp((target - acc) / weights[chosen], 0.0f, kOneMinusEpsilon);
  return true;
}

bool EmitterSampler::chooses_triangles(float* u_select, int* light, float* pmf) const {
  if (delta_.empty() || triangle_share_ >= 1.0f) return true;
  if (*u_select < triangle_share_) {
    *u_select = std::min(*u_select / triangle_share_, kOneMinusEpsilon);
    return true;
  }
  const float u = std::min((*u_select - triangle_share_) / (1.0f - triangle_share_), kOneMinusEpsilon);
  *light = delta_distribution_.sample(u, pmf);
  *pmf *= 1.0f - triangle_share_;
  return false;
}

bool EmitterSampler::sample_delta(int light, float pmf, const glm::vec3& reference, EmitterSample* out) const {
  DeltaIllumination seen;
  if (light < 0 || !(pmf > 0.0f) || !delta_.illuminate(light, reference, &seen)) return false;
  out->position = seen.position;
  out->normal = -seen.wi;
  out->wi = seen.wi;
  out->distance = seen.distance;
  out->radiance = seen.irradiance;
  out->pdf = pmf;
  out->mesh = out->triangle = -1;
  out->light = light;
  out->delta = true;
  return true;
}

bool EmitterSampler::sample(const glm::vec3& reference, float u_select, const glm::vec2& u_point, EmitterSample* out,
                            bool punctual) const {
  if (!punctual && triangles_.empty()) return false;
  float pmf = 0.0f;
  int index = -1;
  if (spatial_) {
    int entry;
    float entry_pmf, remapped;
    if (!choose_spatially(reference, u_select, punctual, &entry, &entry_pmf, &remapped)) return false;
    if (size_t(entry) >= clusters_.size()) return sample_delta(entry - int(clusters_.size()), entry_pmf, reference, out);
    float in_cluster = 0.0f;
    index = choose_in_cluster(clusters_[size_t(entry)], reference, remapped, &in_cluster);
    if (index < 0) return false;
    pmf = entry_pmf * in_cluster;
  } else {
    int light = -1;
    float light_pmf = 0.0f;
    if (punctual && !chooses_triangles(&u_select, &light, &light_pmf))
      return sample_delta(light, light_pmf, reference, out);
    index = distribution_.sample(u_select, &pmf);
    if (punctual) pmf *= triangle_share_;
  }
  if (index < 0) return false;
  const EmissiveTriangle& e = triangles_[index];
  if (in_plane(e.normal, e.p0, reference)) return false;
  glm::vec2 b12;
  glm::vec3 point;
  Geometry g;
  SphericalTriangle seen;
  if (by_solid_angle(e, reference) && seen.set(reference, e.p0, e.p1, e.p2)) {
    // The point where the sampled direction meets the triangle's plane.
    const glm::vec3 wi = seen.sample(u_point);
    const float toward = glm::dot(e.normal, wi);
    const float t = safe_div(glm::dot(e.normal, e.p0 - reference), toward);
    if (!(t > 0.0f) || !std::isfinite(t)) return false;
    point = reference + t * wi;
    b12 = barycentrics_of(e, point);
    g = solid_angle_sampled(pmf, seen.solid_angle(), e.normal, reference, point);
  } else {
    b12 = sample_uniform_triangle(u_point);
    const glm::vec3 b = barycentrics(b12);
    point = e.p0 + (e.p1 - e.p0) * b.y + (e.p2 - e.p0) * b.z;
    g = area_sampled(pmf, e.area, e.normal, reference, point);
  }
  if (!(g.pdf > 0.0f)) return false;
  const glm::vec3 bary = barycentrics(b12);

  const scenes::Mesh& mesh = scene_->meshes[e.mesh];
  const scenes::Material& material = scene_->materials[mesh.material];
  out->position = point;
  out->normal = e.normal;
  out->wi = g.wi;
  out->distance = g.distance;
  out->pdf = g.pdf;
  out->mesh = e.mesh;
  out->triangle = e.triangle;
  out->delta = false;
  // A one-sided emitter seen from behind sends nothing toward the reference, nor does a
  // cut-out (alpha MASK) part, which the accelerator treats as empty space; a blended one
  // sends alpha of its emission, the share of rays that stop on it (docs/brdf.md).
  const glm::uvec3 tri = mesh.triangles[e.triangle];
  const bool sees_emitting_side = g.cos_light > 0.0f || material.double_sided;
  out->radiance = sees_emitting_side ? coverage_at(*scene_, mesh, material, tri, bary) *
                                           emitted_radiance(*scene_, mesh, material, tri, bary)
                                     : glm::vec3(0.0f);
  return true;
}

float EmitterSampler::pdf(const glm::vec3& reference, int mesh, int triangle, const glm::vec3& point,
                          bool punctual) const {
  if (mesh < 0 || static_cast<size_t>(mesh) >= first_of_mesh_.size() || first_of_mesh_[mesh] < 0) return 0.0f;
  if (triangle < 0 || static_cast<size_t>(triangle) >= scene_->meshes[mesh].triangles.size()) return 0.0f;
  const int index = lookup_[first_of_mesh_[mesh] + triangle];
  if (index < 0) return 0.0f;
  const EmissiveTriangle& e = triangles_[index];
  if (in_plane(e.normal, e.p0, reference)) return 0.0f;
  const float pmf = selection_pmf(reference, index, punctual);
  SphericalTriangle seen;
  if (by_solid_angle(e, reference) && seen.set(reference, e.p0, e.p1, e.p2))
    return solid_angle_sampled(pmf, seen.solid_angle(), e.normal, reference, point).pdf;
  return area_sampled(pmf, e.area, e.normal, reference, point).pdf;
}

float EmitterSampler::delta_pmf(const glm::vec3& reference, int light) const {
  if (light < 0 || light >= delta_.size()) return 0.0f;
  if (spatial_) {
    float total = 0.0f;
    const float* weights = selection_weights_at(reference, true, &total);
    return total > 0.0f ? weights[clusters_.size() + size_t(light)] / total : 0.0f;
  }
  if (triangle_share_ >= 1.0f) return 0.0f;
  return (1.0f - triangle_share_) * delta_distribution_.pmf(light);
}

bool EmitterSampler::by_solid_angle(const EmissiveTriangle& e, const glm::vec3& reference) {
  const glm::vec3 d = e.centroid - reference;
  return e.longest_edge2 > kSolidAngleExtent * kSolidAngleExtent * glm::dot(d, d);
}

}  // namespace phyir::render
