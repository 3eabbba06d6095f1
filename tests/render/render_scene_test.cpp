// RenderScene::interact: textures read at the right texel (and transformed), factors
// applied, normals flipped to the arriving side, normal maps, alpha modes, and no NaN from
// degenerate input.
#include "phyir/render/render_scene.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "phyir/core/safe_math.h"
#include "phyir/render/rng.h"
#include "test_scenes.h"

namespace phyir::render {
namespace {

using test::add_material;
using test::add_quad;
using test::add_texture;
using test::make_emitter;
using test::make_material;

// A 2 m x 2 m floor quad in the y = 0 plane facing +Y, UV u along +Z, v along +X
// (corner at (-1, 0, -1)); texel (i, j) of an N x N texture is centred above
// x = -1 + 2 (j + 0.5) / N, z = -1 + 2 (i + 0.5) / N.
int add_floor(scenes::Scene& scene, int material) {
  return add_quad(scene, {-1, 0, -1}, {0, 0, 2}, {2, 0, 0}, material, "floor");
}

glm::vec3 above_texel(int i, int j, int n) {
  return glm::vec3(-1.0f + 2.0f * (j + 0.5f) / n, 1.0f, -1.0f + 2.0f * (i + 0.5f) / n);
}

SurfaceInteraction trace_down(const RenderScene& rs, const glm::vec3& from) {
  SurfaceInteraction si;
  EXPECT_TRUE(rs.trace(Ray{from, {0, -1, 0}}, &si));
  return si;
}

bool all_finite(const SurfaceInteraction& si) {
  return is_finite(si.position) && is_finite(si.geometric_normal) && is_finite(si.shading_normal) &&
         is_finite(si.tangent) && std::isfinite(si.uv.x) && std::isfinite(si.uv.y) &&
         is_finite(si.brdf.base_color) && std::isfinite(si.brdf.roughness) && std::isfinite(si.brdf.metalness) &&
         is_finite(si.emission) && std::isfinite(si.transmission) && std::isfinite(si.opacity);
}

TEST(RenderScene, MetallicRoughnessTextureIsReadPerTexel) {
  // G = roughness, B = metalness; R and A carry junk that must be ignored.
  const std::vector<glm::vec4> texels = {{0.9f, 0.1f, 0.9f, 0.3f}, {0.5f, 0.3f, 0.7f, 1.0f},
                                         {0.2f, 0.6f, 0.2f, 0.0f}, {0.0f, 0.8f, 0.05f, 0.5f}};
  for (const float factor : {1.0f, 0.5f}) {
    scenes::Scene scene;
    scenes::Material m = make_material(glm::vec3(0.5f), factor, factor);
    m.metallic_roughness_texture.texture = add_texture(scene, 2, 2, texels);
    add_floor(scene, add_material(scene, m));
    const RenderScene rs(scene);
    for (int j = 0; j < 2; ++j) {
      for (int i = 0; i < 2; ++i) {
        const SurfaceInteraction si = trace_down(rs, above_texel(i, j, 2));
        const glm::vec4& t = texels[j * 2 + i];
        EXPECT_FLOAT_EQ(si.brdf.roughness, factor * t.y) << "texel " << i << "," << j;
        EXPECT_FLOAT_EQ(si.brdf.metalness, factor * t.z) << "texel " << i << "," << j;
        EXPECT_NEAR(si.uv.x, (i + 0.5f) / 2.0f, 1e-5f);
        EXPECT_NEAR(si.uv.y, (j + 0.5f) / 2.0f, 1e-5f);
      }
    }
  }
}

TEST(RenderScene, UntexturedFactorsAreClamped) {
  scenes::Scene scene;
  add_floor(scene, add_material(scene, make_material(glm::vec3(1.5f, 0.25f, -1.0f), 2.0f, -0.5f)));
  const RenderScene rs(scene);
  const SurfaceInteraction si = trace_down(rs, {0.1f, 1.0f, 0.2f});
  EXPECT_EQ(si.brdf.base_color, glm::vec3(1.0f, 0.25f, 0.0f));
  EXPECT_EQ(si.brdf.roughness, 1.0f);
  EXPECT_EQ(si.brdf.metalness, 0.0f);
  EXPECT_EQ(si.opacity, 1.0f);
  EXPECT_FALSE(si.emits);
  EXPECT_EQ(si.material, 0);
}

TEST(RenderScene, BaseColourIsFactorTimesTextureTimesVertexColour) {
  scenes::Scene scene;
  scenes::Material m = make_material();
  m.base_color_factor = glm::vec4(0.5f, 1.0f, 1.0f, 1.0f);
  m.base_color_texture.texture = add_texture(scene, 2, 2,
                                             {{1.0f, 0.2f, 0.4f, 1.0f}, {0.6f, 0.6f, 0.6f, 1.0f},
                                              {0.8f, 0.1f, 0.0f, 1.0f}, {0.2f, 0.4f, 1.0f, 1.0f}});
  const int mesh = add_floor(scene, add_material(scene, m));
  scene.meshes[mesh].colors.assign(4, glm::vec4(1.0f, 0.5f, 1.0f, 1.0f));
  const RenderScene rs(scene);
  const SurfaceInteraction si = trace_down(rs, above_texel(0, 1, 2));  // texel (0, 1)
  EXPECT_NEAR(si.brdf.base_color.x, 0.5f * 0.8f, 1e-6f);
  EXPECT_NEAR(si.brdf.base_color.y, 0.5f * 0.1f, 1e-6f);
  EXPECT_NEAR(si.brdf.base_color.z, 0.0f, 1e-6f);
}

TEST(RenderScene, TextureTransformAndTexcoordSetArePerSlot) {
  scenes::Scene scene;
  scenes::Material m = make_material(glm::vec3(0.5f), 1.0f, 1.0f);
  const int tex = add_texture(scene, 2, 2, {{0, 0.1f, 0, 1}, {0, 0.3f, 0, 1}, {0, 0.6f, 0, 1}, {0, 0.8f, 0, 1}});
  // Roughness reads TEXCOORD_1 shifted by half the texture in u.
  m.metallic_roughness_texture.texture = tex;
  m.metallic_roughness_texture.texcoord = 1;
  m.metallic_roughness_texture.transform.offset = glm::vec2(0.5f, 0.0f);
  const int mesh = add_floor(scene, add_material(scene, m));
  // TEXCOORD_1 = TEXCOORD_0 mirrored in v.
  for (const glm::vec2& uv : scene.meshes[mesh].texcoords0) scene.meshes[mesh].texcoords1.push_back({uv.x, 1.0f - uv.y});
  const RenderScene rs(scene);
  // Above texel (0, 0) of TEXCOORD_0: TEXCOORD_1 gives (0.25, 0.75), +0.5 in u -> texel (1, 1).
  const SurfaceInteraction si = trace_down(rs, above_texel(0, 0, 2));
  EXPECT_FLOAT_EQ(si.brdf.roughness, 0.8f);
  EXPECT_NEAR(si.uv.x, 0.25f, 1e-5f);  // the interaction's uv is TEXCOORD_0, untransformed
  EXPECT_NEAR(si.uv.y, 0.25f, 1e-5f);
}

TEST(RenderScene, EmissionTransmissionAndAlphaModes) {
  scenes::Scene scene;
  scenes::Material m = make_emitter(glm::vec3(2.0f, 1.0f, 0.5f));
  m.emissive_strength = 3.0f;
  m.emissive_texture.texture = add_texture(scene, 1, 1, {{0.5f, 1.0f, 0.0f, 1.0f}});
  m.transmission_factor = 0.8f;
  m.transmission_texture.texture = add_texture(scene, 1, 1, {{0.5f, 0.0f, 0.0f, 1.0f}});
  m.base_color_factor.w = 0.3f;
  m.alpha_mode = scenes::AlphaMode::Blend;
  m.ior = 1.33f;
  const int mat = add_material(scene, m);
  add_floor(scene, mat);
  {
    const RenderScene rs(scene);
    const SurfaceInteraction si = trace_down(rs, {0.2f, 1.0f, 0.3f});
    EXPECT_TRUE(si.emits);
    EXPECT_NEAR(si.emission.x, 2.0f * 3.0f * 0.5f, 1e-6f);
    EXPECT_NEAR(si.emission.y, 1.0f * 3.0f * 1.0f, 1e-6f);
    EXPECT_NEAR(si.emission.z, 0.0f, 1e-6f);
    EXPECT_NEAR(si.transmission, 0.4f, 1e-6f);
    EXPECT_NEAR(si.opacity, 0.3f, 1e-6f);
    EXPECT_FLOAT_EQ(si.ior, 1.33f);
  }
  scene.materials[mat].alpha_mode = scenes::AlphaMode::Opaque;
  EXPECT_EQ(trace_down(RenderScene(scene), {0.2f, 1.0f, 0.3f}).opacity, 1.0f);
  // MASK above the cutoff is opaque (hits below the cutoff never reach interact: the
  // accelerator's filter drops them; see AlphaMaskLetsRaysThroughTransparentTexels).
  scene.materials[mat].alpha_mode = scenes::AlphaMode::Mask;
  scene.materials[mat].alpha_cutoff = 0.25f;
  EXPECT_EQ(trace_down(RenderScene(scene), {0.2f, 1.0f, 0.3f}).opacity, 1.0f);
}

TEST(RenderScene, BackFaceHitsFlipBothNormals) {
  scenes::Scene scene;
  add_floor(scene, add_material(scene, make_emitter(glm::vec3(1.0f))));
  const RenderScene rs(scene);
  SurfaceInteraction front, back;
  ASSERT_TRUE(rs.trace(Ray{{0.1f, 1.0f, 0.1f}, {0, -1, 0}}, &front));
  ASSERT_TRUE(rs.trace(Ray{{0.1f, -1.0f, 0.1f}, {0, 1, 0}}, &back));
  EXPECT_TRUE(front.front_face);
  EXPECT_EQ(front.geometric_normal, glm::vec3(0, 1, 0));
  EXPECT_EQ(front.shading_normal, glm::vec3(0, 1, 0));
  EXPECT_FALSE(back.front_face);
  EXPECT_EQ(back.geometric_normal, glm::vec3(0, -1, 0));
  EXPECT_EQ(back.shading_normal, glm::vec3(0, -1, 0));
  EXPECT_NEAR(glm::dot(back.tangent, back.shading_normal), 0.0f, 1e-6f);
  // One-sided emitter: only the front emits.
  EXPECT_TRUE(front.emits);
  EXPECT_FALSE(back.emits);
  EXPECT_EQ(back.emission, glm::vec3(0.0f));
  // Double-sided: both.
  scene.materials[0].double_sided = true;
  const RenderScene rs2(scene);
  ASSERT_TRUE(rs2.trace(Ray{{0.1f, -1.0f, 0.1f}, {0, 1, 0}}, &back));
  EXPECT_TRUE(back.emits);
  EXPECT_EQ(back.emission, glm::vec3(1.0f));
}

TEST(RenderScene, NormalsAlwaysFaceTheIncomingRay) {
  // A sphere hit from outside and from inside, with smooth normals.
  scenes::Scene scene;
  test::add_uv_sphere(scene, {0, 0, 0}, 1.0f, add_material(scene, make_material()), 32, 16);
  const RenderScene rs(scene);
  Rng rng(2, 2);
  int violations = 0;
  for (int i = 0; i < 10000; ++i) {
    const bool inside = i % 2 == 0;
    const glm::vec3 o = inside ? glm::vec3(0.1f, -0.2f, 0.05f) : glm::vec3(0.0f, 0.0f, 3.0f);
    const glm::vec3 target(0.6f * rng.next_float() - 0.3f, 0.6f * rng.next_float() - 0.3f, 0.6f * rng.next_float() - 0.3f);
    const glm::vec3 d = glm::normalize(target - o);
    SurfaceInteraction si;
    ASSERT_TRUE(rs.trace(Ray{o, d}, &si));
    if (si.front_face == inside) ++violations;
    if (glm::dot(d, si.geometric_normal) > 0.0f || glm::dot(si.shading_normal, si.geometric_normal) <= 0.0f) ++violations;
    if (std::abs(glm::length(si.shading_normal) - 1.0f) > 1e-5f) ++violations;
    // Interpolated position is on the sphere's polyhedron, within its sagitta (~0.5% of r).
    if (std::abs(glm::length(si.position) - 1.0f) > 0.01f) ++violations;
  }
  EXPECT_EQ(violations, 0);
}

TEST(RenderScene, DegenerateTrianglesGiveFiniteNormals) {
  scenes::Scene scene;
  const int mat = add_material(scene, make_material());
  scenes::Mesh mesh;
  mesh.name = "degenerate";
  mesh.material = mat;
  mesh.positions = {{0, 0, 0}, {1, 1, 1}, {2, 2, 2}, {5, 5, 5}};  // collinear; and a repeated vertex
  mesh.triangles = {{0, 1, 2}, {3, 3, 3}};
  scene.meshes.push_back(mesh);
  scenes::Mesh with_normals = mesh;
  with_normals.normals.assign(4, glm::vec3(0, 0, 1));
  scene.meshes.push_back(with_normals);
  scenes::Mesh zero_normals = mesh;
  zero_normals.normals.assign(4, glm::vec3(0.0f));
  zero_normals.normals[0].x = std::numeric_limits<float>::quiet_NaN();
  scene.meshes.push_back(zero_normals);
  const RenderScene rs(scene);
  const Ray ray{{3, 0, 0}, glm::normalize(glm::vec3(-1, 1, 0.2f))};
  for (int m = 0; m < 3; ++m) {
    for (int t = 0; t < 2; ++t) {
      Hit hit;
      hit.t = 2.0f;
      hit.mesh = m;
      hit.triangle = t;
      hit.barycentric = {0.3f, 0.3f};
      const SurfaceInteraction si = rs.interact(ray, hit);
      EXPECT_TRUE(all_finite(si)) << "mesh " << m << " triangle " << t;
      EXPECT_NEAR(glm::length(si.geometric_normal), 1.0f, 1e-5f);
      EXPECT_NEAR(glm::length(si.shading_normal), 1.0f, 1e-5f);
      EXPECT_LE(glm::dot(ray.direction, si.geometric_normal), 0.0f);
      if (m == 1) {
        EXPECT_NEAR(std::abs(si.geometric_normal.z), 1.0f, 1e-6f);  // interpolated fallback
      }
    }
  }
}

TEST(RenderScene, NonFiniteTexelsAndFactorsNeverGiveNaN) {
  scenes::Scene scene;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  scenes::Material m = make_material();
  m.roughness_factor = nan;
  m.emissive_factor = glm::vec3(inf, 1.0f, 0.0f);
  m.base_color_texture.texture = add_texture(scene, 1, 1, {{nan, inf, -inf, nan}});
  m.metallic_roughness_texture.texture = add_texture(scene, 1, 1, {{nan, nan, inf, 1}});
  m.normal_texture.texture = add_texture(scene, 1, 1, {{nan, 0.5f, inf, 1}});
  m.alpha_mode = scenes::AlphaMode::Blend;
  add_floor(scene, add_material(scene, m));
  const RenderScene rs(scene);
  // The NaN texel's alpha reads as 0: light passes the blended floor, so the surface is
  // asked for as geometry (the AOVs' query).
  SurfaceInteraction si;
  EXPECT_FALSE(rs.trace(Ray{{0.1f, 1.0f, 0.1f}, {0, -1, 0}}, &si));
  ASSERT_TRUE(rs.trace(Ray{{0.1f, 1.0f, 0.1f}, {0, -1, 0}}, &si, Coverage::kBlendSolid));
  EXPECT_TRUE(all_finite(si));
  EXPECT_EQ(si.opacity, 0.0f);
}

TEST(RenderScene, NormalMapTiltsTheShadingNormal) {
  // Tangent-space normal (0.6, 0, 0.8) encoded as texel (0.8, 0.5, 0.9), scale 1: tilts
  // the shading normal towards the tangent (= edge_u = +Z on the floor).
  scenes::Scene scene;
  scenes::Material m = make_material();
  m.normal_texture.texture = add_texture(scene, 1, 1, {{0.8f, 0.5f, 0.9f, 1.0f}});
  const int mat = add_material(scene, m);
  const int with_tangents = add_floor(scene, mat);
  const int without = add_quad(scene, {-1, -1, -1}, {0, 0, 2}, {2, 0, 0}, mat, "lower floor");
  scene.meshes[without].tangents.clear();
  const RenderScene rs(scene);
  const SurfaceInteraction si = trace_down(rs, {0.1f, 1.0f, 0.1f});
  ASSERT_EQ(si.mesh, with_tangents);
  const glm::vec3 expected = glm::normalize(glm::vec3(0.0f, 0.8f, 0.6f));
  EXPECT_NEAR(si.shading_normal.x, expected.x, 1e-5f);
  EXPECT_NEAR(si.shading_normal.y, expected.y, 1e-5f);
  EXPECT_NEAR(si.shading_normal.z, expected.z, 1e-5f);
  EXPECT_EQ(si.geometric_normal, glm::vec3(0, 1, 0));
  EXPECT_NEAR(glm::dot(si.tangent, si.shading_normal), 0.0f, 1e-6f);
  EXPECT_NEAR(glm::length(si.tangent), 1.0f, 1e-6f);
  // Hit from below, both normals flip together.
  SurfaceInteraction below;
  ASSERT_TRUE(rs.trace(Ray{{0.1f, -0.5f, 0.1f}, {0, 1, 0}}, &below));
  ASSERT_EQ(below.mesh, with_tangents);
  EXPECT_NEAR(below.shading_normal.y, -expected.y, 1e-5f);
  EXPECT_NEAR(below.shading_normal.z, -expected.z, 1e-5f);
  // Without tangents the normal map is skipped (with a warning at construction).
  SurfaceInteraction plain;
  ASSERT_TRUE(rs.trace(Ray{{0.1f, -0.5f, 0.1f}, {0, -1, 0}}, &plain));
  ASSERT_EQ(plain.mesh, without);
  EXPECT_EQ(plain.shading_normal, glm::vec3(0, 1, 0));
}

TEST(RenderScene, PositionLiesOnTheTriangleFarFromTheOrigin) {
  // 1e4 m away a ray's t carries ~1e-3 m of error; the barycentric position does not leave
  // the plane by more than the coordinates' own rounding.
  scenes::Scene scene;
  add_quad(scene, {1.0e4f, -5.0f, -5.0f}, {0, 10, 0}, {0, 0, 10}, add_material(scene, make_material()));
  const RenderScene rs(scene);
  Rng rng(8, 8);
  float worst = 0.0f;
  for (int i = 0; i < 1000; ++i) {
    const glm::vec3 target(1.0e4f, 8.0f * rng.next_float() - 4.0f, 8.0f * rng.next_float() - 4.0f);
    const glm::vec3 o(0.0f, 3.0f, -2.0f);
    SurfaceInteraction si;
    ASSERT_TRUE(rs.trace(Ray{o, glm::normalize(target - o)}, &si));
    worst = std::max(worst, std::abs(si.position.x - 1.0e4f));
  }
  EXPECT_EQ(worst, 0.0f) << "an axis-aligned plane at x = 1e4 is exactly representable";
}

}  // namespace
}  // namespace phyir::render
