#include "phyir/render/accelerator.h"

#include <embree3/rtcore.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <limits>
#include <mutex>
#include <string>

#include "phyir/core/error.h"
#include "phyir/core/pcg32.h"
#include "phyir/render/material_eval.h"

namespace phyir::render {

namespace {

// Embree rejects vertices beyond about 1.8e18 in magnitude; anything near that is a
// broken transform anyway.
constexpr float kMaxCoordinate = 1e18f;

const char* error_name(RTCError code) {
  switch (code) {
    case RTC_ERROR_NONE: return "none";
    case RTC_ERROR_UNKNOWN: return "unknown error";
    case RTC_ERROR_INVALID_ARGUMENT: return "invalid argument";
    case RTC_ERROR_INVALID_OPERATION: return "invalid operation";
    case RTC_ERROR_OUT_OF_MEMORY: return "out of memory";
    case RTC_ERROR_UNSUPPORTED_CPU: return "unsupported CPU";
    case RTC_ERROR_CANCELLED: return "cancelled";
  }
  return "unrecognised error";
}

// Why a mesh cannot go to Embree, or "" when it can.
std::string geometry_problem(const scenes::Mesh& mesh) {
  for (size_t i = 0; i < mesh.positions.size(); ++i) {
    const glm::vec3& p = mesh.positions[i];
    for (int k = 0; k < 3; ++k)
      if (!std::isfinite(p[k]) || std::abs(p[k]) > kMaxCoordinate)
        return fmt::format("position {} is ({}, {}, {})", i, p.x, p.y, p.z);
  }
  const size_t n = mesh.positions.size();
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    const glm::uvec3& tri = mesh.triangles[t];
    if (tri.x >= n || tri.y >= n || tri.z >= n)
      return fmt::format("triangle {} indexes vertex ({}, {}, {}) of {}", t, tri.x, tri.y, tri.z, n);
  }
  return {};
}

// What the coverage filter needs to evaluate alpha at a hit.
struct CoverageData {
  const scenes::Scene* scene;
  const scenes::Mesh* mesh;
  const scenes::Material* material;
};

// Embree hands the filter the context it was given; ours carries the query's coverage mode
// and, for transmittance queries, the product so far and the blended primitives already
// counted (Embree may report one primitive more than once: spatial splits put it in
// several leaves).
struct CoverageContext {
  RTCIntersectContext base;  // first member: Embree sees only this
  Coverage mode;
  bool product = false;  // transmittance(): blended surfaces multiply, the query goes on
  float transmittance = 1.0f;
  static constexpr int kCounted = 8;
  int counted = 0;
  uint64_t counted_ids[kCounted] = {};

  // False when this primitive was already counted; records it otherwise (when full, the
  // caller falls back to the stochastic decision, which repeats consistently).
  bool first_report(uint64_t id, bool* recorded) {
    for (int k = 0; k < counted; ++k)
      if (counted_ids[k] == id) return false;
    *recorded = counted < kCounted;
    if (*recorded) counted_ids[counted++] = id;
    return true;
  }
};

// A uniform number in [0, 1) that depends only on the ray and the primitive: Embree may
// report one primitive more than once (spatial splits put it in several leaves) and every
// report must take the same decision; it is the same whatever thread traces the ray.
float coverage_variate(const RTCFilterFunctionNArguments* args, unsigned i, unsigned prim, unsigned geom) {
  RTCRayN* ray = args->ray;
  const unsigned n = args->N;
  const float parts[6] = {RTCRayN_org_x(ray, n, i), RTCRayN_org_y(ray, n, i), RTCRayN_org_z(ray, n, i),
                          RTCRayN_dir_x(ray, n, i), RTCRayN_dir_y(ray, n, i), RTCRayN_dir_z(ray, n, i)};
  uint64_t h = mix64((uint64_t(geom) << 32) | prim);
  for (float f : parts) {
    uint32_t bits;
    std::memcpy(&bits, &f, sizeof bits);
    h = mix64(h ^ bits);
  }
  return float(h >> 40) * 0x1.0p-24f;
}

// glTF's alpha coverage (alphaMode MASK and BLEND), for closest-hit and occlusion queries
// alike: MASK drops hits below the cutoff, so cut-out leaves and grilles let light through;
// BLEND keeps a hit with probability alpha (stochastic coverage, docs/brdf.md), so on
// average a fraction 1 - alpha of what lies behind shows through. Queries about geometry
// rather than light ask for blended surfaces as solid or as absent instead.
void coverage_filter(const RTCFilterFunctionNArguments* args) {
  const auto* data = static_cast<const CoverageData*>(args->geometryUserPtr);
  auto* context = reinterpret_cast<CoverageContext*>(args->context);
  const Coverage mode = context->mode;
  const bool blend = data->material->alpha_mode == scenes::AlphaMode::Blend;
  if (blend && mode == Coverage::kBlendSolid) return;
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] != -1) continue;
    if (blend && mode == Coverage::kBlendAbsent) {
      args->valid[i] = 0;
      continue;
    }
    const unsigned prim = RTCHitN_primID(args->hit, args->N, i);
    const glm::vec2 b12(RTCHitN_u(args->hit, args->N, i), RTCHitN_v(args->hit, args->N, i));
    const float covered = coverage_at(*data->scene, *data->mesh, *data->material, data->mesh->triangles[prim],
                                      barycentrics(b12));
    const unsigned geom = RTCHitN_geomID(args->hit, args->N, i);
    if (blend && context->product) {
      // The product of (1 - alpha) over the blended surfaces crossed; the query goes on.
      bool recorded = false;
      if (context->first_report((uint64_t(geom) << 32) | prim, &recorded)) {
        if (recorded) {
          context->transmittance *= 1.0f - covered;
          args->valid[i] = 0;
          continue;
        }
      } else {
        args->valid[i] = 0;
        continue;
      }
    }
    // MASK: covered is 0 or 1; BLEND: kept with probability `covered`.
    const bool kept = blend ? coverage_variate(args, i, prim, geom) < covered : covered > 0.0f;
    if (!kept) args->valid[i] = 0;
  }
}

CoverageContext coverage_context(Coverage mode) {
  CoverageContext context;
  rtcInitIntersectContext(&context.base);
  context.mode = mode;
  return context;
}

// Embree picks its kernels by the processor. PHYIR_EMBREE_MAX_ISA (sse2, sse4.2, avx, avx2,
// avx512) caps them, so that one machine can run another processor's code paths
// (scripts/test_isa_levels.sh).
std::string device_config() {
  const char* isa = std::getenv("PHYIR_EMBREE_MAX_ISA");
  return isa && *isa ? fmt::format("max_isa={}", isa) : std::string();
}

void fill_ray(const Ray& ray, RTCRay* r) {
  r->org_x = ray.origin.x;
  r->org_y = ray.origin.y;
  r->org_z = ray.origin.z;
  r->dir_x = ray.direction.x;
  r->dir_y = ray.direction.y;
  r->dir_z = ray.direction.z;
  r->tnear = ray.tmin;
  r->tfar = ray.tmax;
  r->time = 0.0f;
  r->mask = 0xFFFFFFFFu;
  r->id = 0;
  r->flags = 0;
}

}  // namespace

struct Accelerator::Impl {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  std::deque<CoverageData> coverage;  // stable addresses for the filters' user pointers

  std::mutex error_mutex;
  std::string first_error;

  ~Impl() {
    if (scene) rtcReleaseScene(scene);
    if (device) rtcReleaseDevice(device);
  }

  static void on_error(void* user, RTCError code, const char* message) {
    auto* self = static_cast<Impl*>(user);
    const std::string text = fmt::format("Embree: {} ({})", message ? message : "", error_name(code));
    spdlog::error("{}", text);
    std::lock_guard<std::mutex> lock(self->error_mutex);
    if (self->first_error.empty()) self->first_error = text;
  }

  // Turns an error recorded by the callback into phyir::Error.
  void check(const std::string& source, const char* step) {
    std::lock_guard<std::mutex> lock(error_mutex);
    if (!first_error.empty()) fail("{}: {} while {}", source, first_error, step);
  }
};

Accelerator::Accelerator(const scenes::Scene& scene) : impl_(std::make_unique<Impl>()) {
  const std::string source = scene.source.empty() ? std::string("<scene>") : scene.source;

  impl_->device = rtcNewDevice(device_config().c_str());
  if (!impl_->device)
    fail("{}: cannot create the Embree device ({})", source, error_name(rtcGetDeviceError(nullptr)));
  rtcSetDeviceErrorFunction(impl_->device, &Impl::on_error, impl_.get());

  impl_->scene = rtcNewScene(impl_->device);
  impl_->check(source, "creating the scene");
  // Robust mode: watertight-ish traversal that does not lose hits on edges and thin or
  // edge-on geometry (at a small speed cost).
  rtcSetSceneFlags(impl_->scene, RTC_SCENE_FLAG_ROBUST);
  rtcSetSceneBuildQuality(impl_->scene, RTC_BUILD_QUALITY_HIGH);

  impl_->coverage.clear();
  for (size_t m = 0; m < scene.meshes.size(); ++m) {
    const scenes::Mesh& mesh = scene.meshes[m];
    // Skipped meshes leave their geometry id unused, so ids stay mesh indices.
    if (mesh.triangles.empty() || mesh.positions.empty()) continue;
    if (const std::string problem = geometry_problem(mesh); !problem.empty()) {
      spdlog::warn("{}: mesh {} ('{}') skipped: {}", source, m, mesh.name, problem);
      continue;
    }

    RTCGeometry geom = rtcNewGeometry(impl_->device, RTC_GEOMETRY_TYPE_TRIANGLE);
    impl_->check(source, fmt::format("creating the geometry of mesh {}", m).c_str());
    auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(
        geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), mesh.positions.size()));
    auto* indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
        geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), mesh.triangles.size()));
    if (!vertices || !indices) {
      rtcReleaseGeometry(geom);
      impl_->check(source, fmt::format("allocating the buffers of mesh {}", m).c_str());
      fail("{}: Embree could not allocate the buffers of mesh {} ('{}')", source, m, mesh.name);
    }
    static_assert(sizeof(glm::vec3) == 3 * sizeof(float) && sizeof(glm::uvec3) == 3 * sizeof(unsigned));
    std::memcpy(vertices, mesh.positions.data(), mesh.positions.size() * sizeof(glm::vec3));
    std::memcpy(indices, mesh.triangles.data(), mesh.triangles.size() * sizeof(glm::uvec3));
    rtcSetGeometryBuildQuality(geom, RTC_BUILD_QUALITY_HIGH);

    if (mesh.material >= 0 && static_cast<size_t>(mesh.material) < scene.materials.size()) {
      const scenes::Material& material = scene.materials[mesh.material];
      // Opaque meshes get no filter: a scene without alpha runs no code for it.
      if (material.alpha_mode != scenes::AlphaMode::Opaque) {
        impl_->coverage.push_back(CoverageData{&scene, &mesh, &material});
        rtcSetGeometryUserData(geom, &impl_->coverage.back());
        rtcSetGeometryIntersectFilterFunction(geom, &coverage_filter);
        rtcSetGeometryOccludedFilterFunction(geom, &coverage_filter);
      }
    }

    rtcCommitGeometry(geom);
    rtcAttachGeometryByID(impl_->scene, geom, static_cast<unsigned>(m));
    rtcReleaseGeometry(geom);  // the scene holds its own reference
    impl_->check(source, fmt::format("adding mesh {} ('{}')", m, mesh.name).c_str());
  }

  rtcCommitScene(impl_->scene);
  impl_->check(source, "building the BVH");
}

Accelerator::~Accelerator() = default;

bool Accelerator::intersect(const Ray& ray, Hit* hit, Coverage coverage) const {
  CoverageContext context = coverage_context(coverage);
  RTCRayHit rh;
  fill_ray(ray, &rh.ray);
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.primID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(impl_->scene, &context.base, &rh);
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return false;
  hit->t = rh.ray.tfar;
  hit->mesh = static_cast<int>(rh.hit.geomID);
  hit->triangle = static_cast<int>(rh.hit.primID);
  hit->barycentric = glm::vec2(rh.hit.u, rh.hit.v);
  return true;
}

float Accelerator::transmittance(const Ray& ray) const {
  CoverageContext context = coverage_context(Coverage::kStochastic);
  context.product = true;
  RTCRay r;
  fill_ray(ray, &r);
  rtcOccluded1(impl_->scene, &context.base, &r);
  if (r.tfar == -std::numeric_limits<float>::infinity()) return 0.0f;
  return context.transmittance;
}

bool Accelerator::occluded(const Ray& ray, Coverage coverage) const {
  CoverageContext context = coverage_context(coverage);
  RTCRay r;
  fill_ray(ray, &r);
  rtcOccluded1(impl_->scene, &context.base, &r);
  // Embree sets tfar to -inf when it finds any hit.
  return r.tfar == -std::numeric_limits<float>::infinity();
}

void Accelerator::intersect_batch(const Ray* rays, size_t count, float* t_out) const {
  constexpr size_t kLanes = 16;
  CoverageContext context = coverage_context(Coverage::kStochastic);
  alignas(64) RTCRayHit16 packet;
  alignas(64) int valid[kLanes];
  for (size_t start = 0; start < count; start += kLanes) {
    const size_t n = std::min(kLanes, count - start);
    for (size_t i = 0; i < kLanes; ++i) {
      // Padding lanes are masked out and given a harmless ray.
      const bool live = i < n;
      const Ray& r = rays[start + (live ? i : 0)];
      valid[i] = live ? -1 : 0;
      packet.ray.org_x[i] = r.origin.x;
      packet.ray.org_y[i] = r.origin.y;
      packet.ray.org_z[i] = r.origin.z;
      packet.ray.dir_x[i] = r.direction.x;
      packet.ray.dir_y[i] = r.direction.y;
      packet.ray.dir_z[i] = r.direction.z;
      packet.ray.tnear[i] = r.tmin;
      packet.ray.tfar[i] = r.tmax;
      packet.ray.time[i] = 0.0f;
      packet.ray.mask[i] = 0xFFFFFFFFu;
      packet.ray.id[i] = static_cast<unsigned>(i);
      packet.ray.flags[i] = 0;
      packet.hit.geomID[i] = RTC_INVALID_GEOMETRY_ID;
      packet.hit.primID[i] = RTC_INVALID_GEOMETRY_ID;
      packet.hit.instID[0][i] = RTC_INVALID_GEOMETRY_ID;
    }
    rtcIntersect16(valid, impl_->scene, &context.base, &packet);
    for (size_t i = 0; i < n; ++i)
      t_out[start + i] = packet.hit.geomID[i] == RTC_INVALID_GEOMETRY_ID
                             ? std::numeric_limits<float>::infinity()
                             : packet.ray.tfar[i];
  }
}

}  // namespace phyir::render
