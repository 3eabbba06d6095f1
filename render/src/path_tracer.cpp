#include "phyir/render/path_tracer.h"

#include <algorithm>

#include "phyir/core/safe_math.h"
#include "phyir/render/brdf.h"
#include "phyir/render/dielectric.h"
#include "phyir/render/frame.h"
#include "phyir/render/ray_offset.h"
#include "phyir/render/rng.h"

namespace phyir::render {

namespace {

// Purposes of the per-bounce random streams.
enum Stream : uint64_t { kBrdfStream = 1, kEmitterStream = 2, kEnvironmentStream = 3, kRouletteStream = 4, kGlassStream = 5 };

Rng bounce_rng(uint64_t path_key, int bounce, Stream purpose) {
  return Rng(mix64(path_key ^ mix64(uint64_t(bounce) * 8 + purpose)), purpose);
}

// Shading frame at a hit, with wo on the positive side. Falls back to the geometric
// normal when the shading normal would put the viewer below the surface.
Frame shading_frame(const SurfaceInteraction& si, const glm::vec3& wo_world) {
  if (glm::dot(si.shading_normal, wo_world) > 0.0f) return Frame(si.shading_normal);
  return Frame(si.geometric_normal);
}

template <bool kEmitters, bool kEnvironment, bool kTransmission>
glm::vec3 trace_path(const RenderScene& scene, const PathSettings& settings, const Ray& camera_ray,
                     uint64_t path_key, const FirstBounceSamples* first, PathCounters* counters) {
  glm::vec3 L(0.0f);
  glm::vec3 beta(1.0f);
  Ray ray = camera_ray;
  bool previous_delta = true;  // the camera ray counts as a delta "bounce": no MIS
  float previous_pdf = 0.0f;
  glm::vec3 previous_position = ray.origin;
  const EnvironmentLight* environment = kEnvironment ? scene.environment() : nullptr;
  ++counters->paths;

  for (int bounce = 0;; ++bounce) {
    SurfaceInteraction si;
    ++counters->rays;
    if (!scene.trace(ray, &si)) {
      if (environment) {
        const glm::vec3 Le = environment->radiance(ray.direction);
        const float w = previous_delta ? 1.0f
                                       : power_heuristic(previous_pdf, environment->pdf(ray.direction));
        L += beta * Le * w;
      }
      break;
    }
    if (si.emits) {
      float w = 1.0f;
      if (kEmitters && !previous_delta) {
        const float light_pdf = scene.emitters().pdf(previous_position, si.mesh, si.triangle, si.position);
        w = power_heuristic(previous_pdf, light_pdf);
      }
      L += beta * si.emission * w;
    }
    if (bounce >= settings.max_bounces) break;

    const glm::vec3 wo_world = -ray.direction;

    // Glass: a delta dielectric lobe chosen with probability `transmission`.
    if constexpr (kTransmission) {
      if (si.transmission > 0.0f) {
        Rng rng = bounce_rng(path_key, bounce, kGlassStream);
        if (rng.next_float() < si.transmission) {
          // Geometric normal faces the ray; `entering` when the ray hit the front face.
          const Frame frame(si.geometric_normal);
          // An IOR of 1 (or less) is no interface: keep eta just above 1 so the Fresnel
          // and refraction formulas stay defined (glTF allows ior = 1 as a special case).
          const float eta = std::max(si.ior, 1.0f + 1e-4f);
          const DielectricSample ds =
              sample_dielectric(frame.to_local(wo_world), eta, si.front_face, si.brdf.base_color, rng.next_float());
          const glm::vec3 wi = frame.to_world(ds.wi);
          beta *= ds.weight;
          previous_delta = true;
          previous_position = si.position;
          ray = Ray{spawn_origin(si.position, si.geometric_normal, wi), wi};
          if (max_component(beta) <= 0.0f) break;
          continue;
        }
      }
    }

    const Frame frame = shading_frame(si, wo_world);
    const glm::vec3 wo = frame.to_local(wo_world);

    // Next-event estimation on emissive triangles (non-delta part of the BRDF only).
    if constexpr (kEmitters) {
      Rng rng = bounce_rng(path_key, bounce, kEmitterStream);
      float u_select = rng.next_float();
      glm::vec2 u_point = rng.next_2d();
      if (first && bounce == 0) u_select = first->light_select, u_point = first->light_point;
      EmitterSample ls;
      if (scene.emitters().sample(si.position, u_select, u_point, &ls) && ls.pdf > 0.0f &&
          max_component(ls.radiance) > 0.0f) {
        const glm::vec3 wi = frame.to_local(ls.wi);
        const glm::vec3 f = brdf_eval(si.brdf, wo, wi);
        if (wi.z > 0.0f && glm::dot(ls.wi, si.geometric_normal) > 0.0f && max_component(f) > 0.0f) {
          const Ray shadow = shadow_ray_to(si.position, si.geometric_normal, ls.position, ls.normal);
          ++counters->rays;
          if (!scene.accelerator().occluded(shadow)) {
            const float w = power_heuristic(ls.pdf, brdf_pdf(si.brdf, wo, wi));
            L += beta * f * ls.radiance * (wi.z * w / ls.pdf);
          }
        }
      }
    }
    if constexpr (kEnvironment) {
      if (environment) {
        Rng rng = bounce_rng(path_key, bounce, kEnvironmentStream);
        glm::vec3 wi_world, Le;
        float pdf;
        if (environment->sample(rng.next_2d(), &wi_world, &Le, &pdf) && pdf > 0.0f) {
          const glm::vec3 wi = frame.to_local(wi_world);
          const glm::vec3 f = brdf_eval(si.brdf, wo, wi);
          if (wi.z > 0.0f && glm::dot(wi_world, si.geometric_normal) > 0.0f && max_component(f) > 0.0f) {
            const Ray shadow{spawn_origin(si.position, si.geometric_normal, wi_world), wi_world};
            ++counters->rays;
            if (!scene.accelerator().occluded(shadow)) {
              const float w = power_heuristic(pdf, brdf_pdf(si.brdf, wo, wi));
              L += beta * f * Le * (wi.z * w / pdf);
            }
          }
        }
      }
    }

    // Continue the path by sampling the BRDF.
    Rng rng = bounce_rng(path_key, bounce, kBrdfStream);
    float u_lobe = rng.next_float();
    glm::vec2 u_brdf = rng.next_2d();
    if (first && bounce == 0) u_lobe = first->lobe, u_brdf = first->brdf;
    BrdfSample bs;
    if (!brdf_sample(si.brdf, wo, u_lobe, u_brdf, &bs)) break;
    const glm::vec3 wi_world = frame.to_world(bs.wi);
    // Light leaking through the geometric surface (shading normals) ends the path.
    if (glm::dot(wi_world, si.geometric_normal) <= 0.0f) break;
    beta *= bs.weight;
    previous_delta = bs.delta;
    previous_pdf = bs.pdf;
    previous_position = si.position;
    ray = Ray{spawn_origin(si.position, si.geometric_normal, wi_world), wi_world};

    if (bounce + 1 >= settings.roulette_start) {
      const float survive = std::min(0.95f, max_component(beta));
      Rng rr = bounce_rng(path_key, bounce, kRouletteStream);
      if (!(rr.next_float() < survive)) break;
      beta /= survive;
    }
    if (!(max_component(beta) > 0.0f)) break;
  }

  if (!is_finite(L)) {
    ++counters->nonfinite_samples;
    return glm::vec3(0.0f);
  }
  return L;
}

}  // namespace

PathTracer::PathTracer(const RenderScene& scene, const Effects& effects, const PathSettings& settings)
    : scene_(&scene), effects_(effects), settings_(settings) {
  const int key = (effects.emitters ? 4 : 0) | (effects.environment ? 2 : 0) | (effects.transmission ? 1 : 0);
  static constexpr Kernel kKernels[8] = {
      &trace_path<false, false, false>, &trace_path<false, false, true>,
      &trace_path<false, true, false>,  &trace_path<false, true, true>,
      &trace_path<true, false, false>,  &trace_path<true, false, true>,
      &trace_path<true, true, false>,   &trace_path<true, true, true>,
  };
  kernel_ = kKernels[key];
}

glm::vec3 PathTracer::radiance(const Ray& ray, uint64_t path_key, PathCounters* counters) const {
  return kernel_(*scene_, settings_, ray, path_key, nullptr, counters);
}

glm::vec3 PathTracer::radiance(const Ray& ray, uint64_t path_key, const FirstBounceSamples& first,
                               PathCounters* counters) const {
  return kernel_(*scene_, settings_, ray, path_key, &first, counters);
}

uint64_t PathTracer::path_key(uint64_t seed, uint64_t pixel, uint64_t sample) {
  return mix64(mix64(seed) ^ mix64(pixel * 0x100000001B3ull + sample));
}

}  // namespace phyir::render
