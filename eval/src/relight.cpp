#include "phyir/eval/relight.h"

#include <algorithm>
#include <cmath>
#include <memory>

#include "phyir/render/camera.h"
#include "phyir/render/environment_light.h"
#include "phyir/render/render_scene.h"
#include "phyir/render/render_view.h"
#include "phyir/scenes/scene.h"

namespace phyir::eval {
namespace {

// A UV sphere with smooth outward normals (enough segments that its silhouette and
// highlights are round at 64 pixels).
scenes::Mesh uv_sphere(float radius, int segments, int rings) {
  scenes::Mesh mesh;
  mesh.name = "relight sphere";
  mesh.material = 0;
  const double pi = M_PI;
  for (int r = 0; r <= rings; ++r) {
    const double theta = pi * r / rings;
    for (int s = 0; s <= segments; ++s) {
      const double phi = 2.0 * pi * s / segments;
      const glm::vec3 n(float(std::sin(theta) * std::sin(phi)), float(std::cos(theta)),
                        float(std::sin(theta) * std::cos(phi)));
      mesh.positions.push_back(radius * n);
      mesh.normals.push_back(n);
      mesh.texcoords0.push_back(glm::vec2(float(s) / segments, float(r) / rings));
    }
  }
  const unsigned stride = unsigned(segments + 1);
  for (int r = 0; r < rings; ++r)
    for (int s = 0; s < segments; ++s) {
      const unsigned i00 = r * stride + s, i01 = i00 + 1, i10 = i00 + stride, i11 = i10 + 1;
      if (r != 0) mesh.triangles.push_back(glm::uvec3(i00, i10, i01));
      if (r != rings - 1) mesh.triangles.push_back(glm::uvec3(i01, i10, i11));
    }
  return mesh;
}

}  // namespace

const std::array<SphereMaterial, 3>& sphere_materials() {
  static const std::array<SphereMaterial, 3> materials = {{
      {"diffuse", "Diffuse", glm::vec3(0.5f), 1.0f, 0.0f},
      {"matte_silver", "Matte silver", glm::vec3(0.972f, 0.960f, 0.915f), 0.5f, 1.0f},
      {"mirror_silver", "Mirror silver", glm::vec3(0.972f, 0.960f, 0.915f), 0.0f, 1.0f},
  }};
  return materials;
}

scenes::Scene material_sphere(const SphereMaterial& material, float radius, int segments, int rings) {
  scenes::Scene scene;
  scene.source = "sphere (" + material.key + ")";
  scenes::Material m;
  m.name = material.key;
  m.base_color_factor = glm::vec4(material.base_color, 1.0f);
  m.roughness_factor = material.roughness;
  m.metallic_factor = material.metalness;
  scene.materials.push_back(m);
  scene.meshes.push_back(uv_sphere(radius, segments, rings));
  for (const glm::vec3& p : scene.meshes[0].positions) scene.bounds.extend(p);
  return scene;
}

RelitSphere relight_sphere(const Image& probe, const SphereMaterial& material, const RelightSettings& settings) {
  const scenes::Scene scene = material_sphere(material, 1.0f, 96, 48);

  // Radiance cannot be negative; a method's probe might be (the environment's sampling
  // distribution needs non-negative texels).
  Image light = probe;
  for (float& v : light.pixels) v = std::max(v, 0.0f);
  const render::RenderScene rs(scene, std::make_unique<render::EnvironmentLight>(light));
  render::CameraModel camera;
  camera.projection = render::Projection::Perspective;
  camera.position = glm::vec3(0.0f, 0.0f, 3.0f);
  camera.forward = glm::vec3(0.0f, 0.0f, -1.0f);
  camera.up = glm::vec3(0.0f, 1.0f, 0.0f);
  camera.yfov = float(2.0 * std::asin(1.0 / 3.0) * 1.08);
  camera.width = camera.height = settings.size;

  render::RenderSettings rset;
  rset.spp = settings.spp;
  rset.seed = settings.seed;
  rset.path.max_bounces = settings.max_bounces;
  rset.aovs = true;
  rset.progress = false;
  const render::RenderOutput out = render::render_view(rs, camera, rset);
  RelitSphere result;
  result.color = out.film.color();
  result.mask = out.film.aov("mask_geometry");
  return result;
}

}  // namespace phyir::eval
