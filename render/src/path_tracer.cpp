#include "phyir/render/path_tracer.h"

#include <algorithm>

#include "phyir/core/safe_math.h"
#include "phyir/render/brdf.h"
#include "phyir/render/dielectric.h"
#include "phyir/render/direct_lighting.h"
#include "phyir/render/frame.h"
#include "phyir/render/guide_mixture.h"
#include "phyir/render/ray_offset.h"
#include "phyir/render/streams.h"
#include "path_records.h"

namespace phyir::render {

namespace {

// One path, bounce by bounce. The template flags drop the code of effects the scene lacks.
// kEmitters: next-event estimation (emissive triangles or punctual lights).
template <bool kEmitters, bool kEnvironment, bool kTransmission>
class PathKernel {
 public:
  PathKernel(const RenderScene& scene, const PathSettings& settings, uint64_t key, int max_bounces,
             PathCounters* counters, PathRecords* records)
      : scene_(scene), settings_(settings), key_(key), max_bounces_(max_bounces), counters_(counters),
        records_(records), environment_(kEnvironment ? scene.environment() : nullptr) {}

  glm::vec3 run(const PathStart& start) {
    ray_ = start.ray;
    previous_position_ = ray_.origin;
    if constexpr (kEmitters) subpaths_ = start.subpaths;
    if (start.hit && start.previous) {
      previous_delta_ = false;
      previous_position_ = start.previous->position;
      previous_pdf_ = start.previous->pdf;
      subpath_drawn_ = true;
      choice_from_ = start.previous->choice_from;
      subpath_valid_ = start.subpath != nullptr;
      if (start.subpath) subpath_ = *start.subpath;
    }
    ++counters_->paths;
    for (int bounce = 0;; ++bounce) {
      if constexpr (kEnvironment) draw_environment_variates(bounce);
      SurfaceInteraction si;
      if (bounce == 0 && start.hit) {
        si = *start.hit;  // its emission is the caller's
      } else if (!arrive(&si)) {
        break;
      }
      if (bounce >= max_bounces_) break;
      if (!scatter(si, bounce, bounce == 0 ? start.first : nullptr)) break;
    }
    if (!is_finite(L_)) {
      ++counters_->nonfinite_samples;
      return glm::vec3(0.0f);
    }
    return L_;
  }

 private:
  // Traces the current ray: the environment where it leaves (false), else the hit and its
  // emission, MIS-weighted against the light sample of the previous bounce.
  bool arrive(SurfaceInteraction* si) {
    ++counters_->rays;
    if (!scene_.trace(ray_, si)) {
      if (environment_) {
        const float w =
            previous_delta_ ? 1.0f : environment_hit_weight(scene_, previous_position_, previous_pdf_, ray_.direction);
        gather(beta_ * environment_->radiance_at(previous_position_, ray_.direction), w);
      }
      return false;
    }
    if (si->emits) {
      float w = 1.0f;
      if (kEmitters && !previous_delta_) w = emitter_hit_weight(scene_, previous_position_, previous_pdf_, *si);
      gather(beta_ * si->emission, w);
    }
    return true;
  }

  // Light found by the current ray: `light` (throughput included) times its MIS weight w; a
  // training path also credits it to its vertices.
  void gather(const glm::vec3& light, float w) {
    L_ += light * w;
    if (records_) records_->gather(light * w);
  }

  // The guide's mixture at a vertex: inactive without a guide, and at mirrors (a delta lobe
  // has no density to mix).
  GuideMixture guide_mixture(const SurfaceInteraction& si) const {
    if (!settings_.guide || is_mirror(si.brdf.roughness)) return GuideMixture{};
    return GuideMixture{&settings_.guide->guide_at(si.position), settings_.guide_bsdf_fraction};
  }

  // Direct light at si and the next ray; false when the path ends.
  bool scatter(const SurfaceInteraction& si, int bounce, const FirstBounceSamples* first) {
    const glm::vec3 wo_world = -ray_.direction;
    if constexpr (kTransmission) {
      if (si.transmission > 0.0f) {
        Rng rng = stream(key_, Purpose::kPathGlass, uint64_t(bounce));
        if (rng.next_float() < si.transmission) return refract(si, wo_world, &rng);
      }
    }
    const ShadingPoint x = shading_point(si, wo_world);
    const GuideMixture mixture = guide_mixture(si);
    add_direct_light(si, x, mixture, bounce, first);
    if constexpr (kEmitters) join_light_subpath(x, mixture, bounce);
    return reflect(si, x, mixture, bounce, first) && roulette(bounce);
  }

  // Glass: a delta dielectric lobe, chosen with probability `transmission`.
  bool refract(const SurfaceInteraction& si, const glm::vec3& wo_world, Rng* rng) {
    const Frame frame(si.geometric_normal);  // faces the ray; `front_face`: entering
    // An IOR of 1 (or less) is no interface: keep eta just above 1 so the Fresnel and
    // refraction formulas stay defined (glTF allows ior = 1 as a special case).
    const float eta = std::max(si.ior, 1.0f + 1e-4f);
    const DielectricSample ds =
        sample_dielectric(frame.to_local(wo_world), eta, si.front_face, si.brdf.base_color, rng->next_float());
    const glm::vec3 wi = frame.to_world(ds.wi);
    beta_ *= ds.weight;
    previous_delta_ = true;
    previous_position_ = si.position;
    ray_ = next_ray(si, wi);
    return !(max_component(beta_) <= 0.0f);  // a NaN goes on, to be counted at the end
  }

  // Next-event estimation (the non-delta part of the BRDF only).
  // Its competing ray is drawn from `mixture`, whose density weighs the light samples.
  void add_direct_light(const SurfaceInteraction& si, const ShadingPoint& x, const GuideMixture& mixture, int bounce,
                        const FirstBounceSamples* first) {
    if constexpr (kEmitters) {
      Rng rng = stream(key_, Purpose::kPathLight, uint64_t(bounce));
      LightVariates u;
      u.select = rng.next_float();
      u.point = rng.next_2d();
      if (first) u.select = first->light_select, u.point = first->light_point;
      DirectLightOptions options;
      options.guide = mixture;
      // Against the light subpath the previous vertex joined (none before the first hit,
      // after a mirror, or at glass, where no subpath can end).
      if (!previous_delta_ && (bounce == 0 ? subpaths_ != nullptr : joins_at(bounce - 1)) && LightSubpaths::joinable(si)) {
        options.subpaths = subpaths_;
        options.previous = PreviousVertex{previous_position_, previous_pdf_, choice_from_};
      }
      gather(sample_emitter_light(scene_, x, u, options, beta_, nullptr, counters_), 1.0f);
    }
    if constexpr (kEnvironment) {
      if (environment_)
        gather(sample_environment_light(scene_, x, environment_u_, portal_u_, beta_, counters_, Lobes::kAll, mixture),
               1.0f);
    }
  }

  // Whether the vertex of `bounce` joins a light subpath.
  bool joins_at(int bounce) const {
    return subpaths_ && bounce + 1 < max_bounces_;
  }

  // The path's light subpath joined at x, where the next vertex would take a next-event
  // estimate to compete with it (the path's last vertex takes none); drawn at the first.
  void join_light_subpath(const ShadingPoint& x, const GuideMixture& mixture, int bounce) {
    if (!joins_at(bounce)) return;
    if (!subpath_drawn_) {
      Rng rng = stream(key_, Purpose::kPathLightSubpath);
      LightSubpathVariates u;
      u.choice = rng.next_float();
      u.direction = rng.next_2d();
      subpath_drawn_ = true;
      choice_from_ = x.position;
      subpath_valid_ = subpaths_->sample(choice_from_, u, &subpath_, counters_);
    }
    if (subpath_valid_) gather(subpaths_->join(x, subpath_, Lobes::kAll, mixture, beta_, counters_), 1.0f);
  }

  // The environment sample's numbers for the vertex the next ray finds, drawn before that
  // ray is traced: the sky's alias bin and texel they select (cache misses in a large map)
  // load while Embree works.
  void draw_environment_variates(int bounce) {
    if (!environment_) return;
    Rng rng = stream(key_, Purpose::kPathEnvironment, uint64_t(bounce));
    const float u_texel = rng.next_float();  // its own statement: argument order is unspecified
    environment_u_ = glm::vec3(u_texel, rng.next_2d());
    environment_->prefetch(environment_u_);
    if (scene_.portals().empty()) return;  // no numbers drawn: such scenes keep their streams
    Rng portal = stream(key_, Purpose::kPathPortal, uint64_t(bounce));
    const float u_choice = portal.next_float();
    portal_u_ = glm::vec3(portal.next_2d(), u_choice);
  }

  // The next ray, by sampling the BRDF, or with a guide the mixture (whose choice has its own
  // stream; the direction's numbers are the BRDF's, stratified at the first bounce).
  bool reflect(const SurfaceInteraction& si, const ShadingPoint& x, const GuideMixture& mixture, int bounce,
               const FirstBounceSamples* first) {
    Rng rng = stream(key_, Purpose::kPathBrdf, uint64_t(bounce));
    float u_lobe = rng.next_float();
    glm::vec2 u_brdf = rng.next_2d();
    if (first) u_lobe = first->lobe, u_brdf = first->brdf;
    BrdfSample bs;
    if (mixture.active()) {
      const float u_choice = stream(key_, Purpose::kPathGuide, uint64_t(bounce)).next_float();
      if (!sample_guide_mixture(mixture, x.brdf, x.frame, x.wo, u_choice, u_lobe, u_brdf, &bs)) return false;
    } else if (!brdf_sample(si.brdf, x.wo, u_lobe, u_brdf, &bs)) {
      return false;
    }
    const glm::vec3 wi_world = x.frame.to_world(bs.wi);
    // Light leaking through the geometric surface (shading normals) ends the path.
    if (glm::dot(wi_world, si.geometric_normal) <= 0.0f) return false;
    beta_ *= bs.weight;
    previous_delta_ = bs.delta;
    previous_pdf_ = bs.pdf;
    previous_position_ = si.position;
    if (records_ && !bs.delta) records_->add_vertex(si.position, wi_world, bs.pdf, beta_);
    ray_ = next_ray(si, wi_world);
    return true;
  }

  // The path's next ray keeps the pixel's cone (pbrt-v4 approximates later bounces' ray
  // differentials by the camera's footprint alike): the footprint grows with the length of
  // the path, so later bounces read the texture level that matches it instead of
  // full-resolution texels, which cost cache misses and add nothing a pixel can resolve.
  Ray next_ray(const SurfaceInteraction& si, const glm::vec3& direction) const {
    Ray next{spawn_origin(si.position, si.geometric_normal, direction), direction};
    next.spread = ray_.spread;
    next.width = ray_.width + ray_.spread * si.distance;
    return next;
  }

  bool roulette(int bounce) {
    if (bounce + 1 >= settings_.roulette_start) {
      const float survive = std::min(0.95f, max_component(beta_));
      Rng rng = stream(key_, Purpose::kPathRoulette, uint64_t(bounce));
      if (!(rng.next_float() < survive)) return false;
      beta_ /= survive;
    }
    return max_component(beta_) > 0.0f;
  }

  const RenderScene& scene_;
  const PathSettings& settings_;
  const uint64_t key_;
  const int max_bounces_;
  PathCounters* counters_;
  PathRecords* records_;  // training a guide only
  const LightSubpaths* subpaths_ = nullptr;
  bool subpath_drawn_ = false, subpath_valid_ = false;  // the path's light subpath
  LightVertex subpath_;
  glm::vec3 choice_from_{0.0f};  // where it chose its light
  const EnvironmentLight* environment_;
  glm::vec3 L_{0.0f};
  glm::vec3 beta_{1.0f};
  Ray ray_;
  bool previous_delta_ = true;  // the first ray counts as a delta "bounce": no MIS
  float previous_pdf_ = 0.0f;
  glm::vec3 previous_position_{0.0f};
  glm::vec3 environment_u_{0.0f};  // draw_environment_variates' numbers for this bounce
  glm::vec3 portal_u_{0.0f};       // and the portals' (light portals only)
};

template <bool kEmitters, bool kEnvironment, bool kTransmission>
glm::vec3 trace_path(const RenderScene& scene, const PathSettings& settings, const PathStart& start, uint64_t key,
                     int max_bounces, PathCounters* counters) {
  using Kernel = PathKernel<kEmitters, kEnvironment, kTransmission>;
  if (!start.records) return Kernel(scene, settings, key, max_bounces, counters, nullptr).run(start);
  PathRecords records(start.records);
  const glm::vec3 L = Kernel(scene, settings, key, max_bounces, counters, &records).run(start);
  records.flush();
  return L;
}

}  // namespace

PathTracer::PathTracer(const RenderScene& scene, const Effects& effects, const PathSettings& settings)
    : scene_(&scene), effects_(effects), settings_(settings),
      subpaths_(settings.light_subpaths && effects.punctual_lights ? LightSubpaths(scene) : LightSubpaths()) {
  const int key = (effects.light_sampling() ? 4 : 0) | (effects.environment ? 2 : 0) | (effects.transmission ? 1 : 0);
  static constexpr Kernel kKernels[8] = {
      &trace_path<false, false, false>, &trace_path<false, false, true>,
      &trace_path<false, true, false>,  &trace_path<false, true, true>,
      &trace_path<true, false, false>,  &trace_path<true, false, true>,
      &trace_path<true, true, false>,   &trace_path<true, true, true>,
  };
  kernel_ = kKernels[key];
}

glm::vec3 PathTracer::radiance(const Ray& ray, uint64_t path_key, PathCounters* counters) const {
  return kernel_(*scene_, settings_, PathStart{ray, nullptr, nullptr, nullptr, light_subpaths()}, path_key,
                 settings_.max_bounces, counters);
}

glm::vec3 PathTracer::radiance(const Ray& ray, uint64_t path_key, const FirstBounceSamples& first,
                               PathCounters* counters) const {
  return kernel_(*scene_, settings_, PathStart{ray, nullptr, &first, nullptr, light_subpaths()}, path_key,
                 settings_.max_bounces, counters);
}

glm::vec3 PathTracer::radiance(const Ray& ray, uint64_t path_key, const FirstBounceSamples& first,
                               PathCounters* counters, guiding::RecordBuffer* records) const {
  return kernel_(*scene_, settings_, PathStart{ray, nullptr, &first, records, light_subpaths()}, path_key,
                 settings_.max_bounces, counters);
}

glm::vec3 PathTracer::continue_from(const SurfaceInteraction& hit, const Ray& ray, uint64_t path_key,
                                    int max_bounces, PathCounters* counters) const {
  return kernel_(*scene_, settings_, PathStart{ray, &hit, nullptr, nullptr, light_subpaths()}, path_key, max_bounces,
                 counters);
}

glm::vec3 PathTracer::continue_from(const SurfaceInteraction& hit, const Ray& ray, const PreviousVertex& previous,
                                    const LightVertex* subpath, uint64_t path_key, int max_bounces,
                                    PathCounters* counters) const {
  return kernel_(*scene_, settings_, PathStart{ray, &hit, nullptr, nullptr, light_subpaths(), &previous, subpath},
                 path_key, max_bounces, counters);
}

}  // namespace phyir::render
