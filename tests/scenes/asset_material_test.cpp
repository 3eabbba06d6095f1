// MTL parsing and the MTL -> metal-roughness mapping of docs/assets.md, on hand-written MTL
// files: one test per row of the table.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "phyir/scenes/asset_material.h"

namespace phyir::scenes {
namespace {

MtlMaterial only(const std::string& mtl) {
  const std::vector<MtlMaterial> materials = parse_mtl(mtl, "test.mtl");
  EXPECT_EQ(materials.size(), 1u);
  return materials.empty() ? MtlMaterial{} : materials[0];
}

AssetMaterial mapped(const std::string& mtl, bool base_texture = false, bool alpha_texture = false) {
  return metal_roughness_from_mtl(only(mtl), base_texture, alpha_texture);
}

float srgb_decoded(float c) { return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f); }

TEST(AssetMtl, ParsesOnlyWhatIsWritten) {
  const std::vector<MtlMaterial> materials = parse_mtl(
      "# comment\nnewmtl first\nKd 0.5 0.25 1\nNs 10\r\n\nnewmtl second one\n  Ks 1 1 1\nd 0.5\nTr 0.2\nNi 1.33\n"
      "illum 4\nPm 0.7\nPr 0.2\nmap_Kd -s 1 1 1 tex/wood.jpg\nmap_d C:\\My Files\\mask.png\n",
      "test.mtl");
  ASSERT_EQ(materials.size(), 2u);
  const MtlMaterial& a = materials[0];
  EXPECT_EQ(a.name, "first");
  ASSERT_TRUE(a.Kd.has_value());
  EXPECT_EQ(*a.Kd, glm::vec3(0.5f, 0.25f, 1.0f));
  EXPECT_FLOAT_EQ(a.Ns.value_or(-1), 10.0f);
  EXPECT_FALSE(a.Ks || a.d || a.Tr || a.Ni || a.Pm || a.Pr || a.illum);  // tinyobjloader's defaults are not "written"
  EXPECT_TRUE(a.map_Kd.empty() && a.map_Kd_raw.empty());
  const MtlMaterial& b = materials[1];
  EXPECT_EQ(b.name, "second one");
  EXPECT_FLOAT_EQ(b.d.value_or(-1), 0.5f);
  EXPECT_FLOAT_EQ(b.Tr.value_or(-1), 0.2f);
  EXPECT_FLOAT_EQ(b.Ni.value_or(-1), 1.33f);
  EXPECT_EQ(b.illum.value_or(-1), 4);
  EXPECT_FLOAT_EQ(b.Pm.value_or(-1), 0.7f);
  EXPECT_FLOAT_EQ(b.Pr.value_or(-1), 0.2f);
  EXPECT_EQ(b.map_Kd, "tex/wood.jpg");  // options parsed away
  EXPECT_EQ(b.map_Kd_raw, "-s 1 1 1 tex/wood.jpg");
  EXPECT_EQ(b.map_d_raw, "C:\\My Files\\mask.png");  // spaces kept in the raw argument
}

TEST(AssetMtl, RoughnessFromPhongExponent) {
  // alpha = sqrt(2 / (Ns + 2)), roughness = sqrt(alpha).
  EXPECT_FLOAT_EQ(roughness_from_phong_exponent(0.0f), 1.0f);
  EXPECT_NEAR(roughness_from_phong_exponent(98.0f), std::sqrt(std::sqrt(0.02f)), 1e-6f);  // 0.376
  EXPECT_NEAR(roughness_from_phong_exponent(1000.0f), 0.2114f, 1e-4f);
  EXPECT_FLOAT_EQ(roughness_from_phong_exponent(-5.0f), 1.0f);  // negative exponents clamp to 0
  EXPECT_NEAR(mapped("newmtl m\nKd 1 1 1\nKs 0.5 0.5 0.5\nNs 98\n").roughness, 0.3761f, 1e-4f);
}

TEST(AssetMtl, DiffuseIsSrgbDecoded) {
  const AssetMaterial m = mapped("newmtl m\nKd 0.5 0.2 0.01\nKs 0.5 0.5 0.5\nNs 96\nillum 2\n");
  EXPECT_NEAR(m.base_color.x, srgb_decoded(0.5f), 1e-6f);  // 0.214
  EXPECT_NEAR(m.base_color.y, srgb_decoded(0.2f), 1e-6f);
  EXPECT_NEAR(m.base_color.z, 0.01f / 12.92f, 1e-7f);
  EXPECT_FLOAT_EQ(m.metallic, 0.0f);
  EXPECT_FLOAT_EQ(m.transmission, 0.0f);
  EXPECT_EQ(m.alpha_mode, AssetAlphaMode::Opaque);
  EXPECT_TRUE(m.double_sided);
  EXPECT_EQ(mapped("newmtl m\nKd 2 -1 0.5\n").base_color, srgb_colour_to_linear({1.0f, 0.0f, 0.5f}));  // clamped
}

TEST(AssetMtl, TextureReplacesDiffuse) {
  EXPECT_EQ(mapped("newmtl m\nKd 0.2 0.3 0.4\nmap_Kd wood.jpg\n", /*base_texture=*/true).base_color, glm::vec3(1.0f));
  // An unresolved texture leaves Kd, as Sweet Home 3D shows it.
  EXPECT_NEAR(mapped("newmtl m\nKd 0.5 0.5 0.5\nmap_Kd wood.jpg\n", false).base_color.x, srgb_decoded(0.5f), 1e-6f);
}

TEST(AssetMtl, NoHighlightIsFullyRough) {
  EXPECT_FLOAT_EQ(mapped("newmtl m\nKd 1 1 1\nKs 1 1 1\nNs 500\nillum 1\n").roughness, 1.0f);  // illum 0/1
  EXPECT_FLOAT_EQ(mapped("newmtl m\nKd 1 1 1\nKs 0 0 0\nNs 500\nillum 2\n").roughness, 1.0f);  // black Ks
  EXPECT_FLOAT_EQ(mapped("newmtl m\nKd 1 1 1\n").roughness, 1.0f);                             // no Ks
  // Ks but no Ns: Java 3D's default shininess 64.
  EXPECT_NEAR(mapped("newmtl m\nKs 0.5 0.5 0.5\n").roughness, roughness_from_phong_exponent(64.0f), 1e-6f);
}

TEST(AssetMtl, PbrExtensionWins) {
  const AssetMaterial m = mapped("newmtl m\nKd 0.8 0.6 0.2\nKs 0 0 0\nNs 5\nPm 0.9\nPr 0.25\n");
  EXPECT_FLOAT_EQ(m.metallic, 0.9f);
  EXPECT_FLOAT_EQ(m.roughness, 0.25f);
  EXPECT_NEAR(m.base_color.x, srgb_decoded(0.8f), 1e-6f);  // Kd is the base colour then
}

TEST(AssetMtl, ColouredStrongSpecularIsMetal) {
  // Gold: weak Kd, coloured Ks (rule A). Base colour: Ks scaled to a maximum of 1, decoded.
  const AssetMaterial gold = mapped("newmtl gold\nKd 0.21 0.17 0.003\nKs 0.56 0.43 0.09\nNs 200\nillum 2\n");
  EXPECT_FLOAT_EQ(gold.metallic, 1.0f);
  EXPECT_NEAR(gold.base_color.x, 1.0f, 1e-6f);
  EXPECT_NEAR(gold.base_color.y, srgb_decoded(0.43f / 0.56f), 1e-5f);
  EXPECT_NEAR(gold.base_color.z, srgb_decoded(0.09f / 0.56f), 1e-5f);
  // Grey strong Ks over dark Kd is glossy black plastic, not metal.
  EXPECT_FLOAT_EQ(mapped("newmtl plastic\nKd 0.01 0.01 0.01\nKs 0.6 0.6 0.6\nNs 150\nillum 2\n").metallic, 0.0f);
  // Coloured but weak Ks (below 0.5), or weaker than Kd: dielectric.
  EXPECT_FLOAT_EQ(mapped("newmtl wood\nKd 0.36 0.1 0.1\nKs 0.38 0.29 0.23\nNs 96\n").metallic, 0.0f);
  EXPECT_FLOAT_EQ(mapped("newmtl paint\nKd 0.9 0.1 0.1\nKs 0.8 0.4 0.4\nNs 96\n").metallic, 0.0f);
  // illum 1 has no specular at all.
  EXPECT_FLOAT_EQ(mapped("newmtl m\nKd 0.1 0.1 0.1\nKs 0.9 0.6 0.1\nillum 1\n").metallic, 0.0f);
}

TEST(AssetMtl, MirrorLikeGreyIsMetal) {
  // Rule B: Ns >= 500, Ks >= 0.9, grey Kd at most 3/4 of Ks.
  const AssetMaterial mirror = mapped("newmtl Mirror\nKd 0.224 0.224 0.224\nKs 2 2 2\nNs 998\nillum 2\n");
  EXPECT_FLOAT_EQ(mirror.metallic, 1.0f);
  EXPECT_EQ(mirror.base_color, glm::vec3(1.0f));
  EXPECT_NEAR(mirror.roughness, roughness_from_phong_exponent(998.0f), 1e-6f);
  // Coloured diffuse under the same highlight: glossy paint.
  EXPECT_FLOAT_EQ(mapped("newmtl Taillights\nKd 0.64 0 0\nKs 1.5 1.5 1.5\nNs 778\n").metallic, 0.0f);
  // Less glossy: a white lacquer.
  EXPECT_FLOAT_EQ(mapped("newmtl lacquer\nKd 0.3 0.3 0.3\nKs 1 1 1\nNs 256\n").metallic, 0.0f);
}

TEST(AssetMtl, SeeThroughIsGlassOrCoverage) {
  // d < 1 with a highlight and no texture: glass, transmission = 1 - d.
  const AssetMaterial glass = mapped("newmtl glass\nKd 0.9 0.9 0.9\nKs 0.5 0.5 0.5\nNs 500\nNi 1.52\nd 0.2\nillum 2\n");
  EXPECT_NEAR(glass.transmission, 0.8f, 1e-6f);
  EXPECT_FLOAT_EQ(glass.alpha, 1.0f);
  EXPECT_FLOAT_EQ(glass.ior, 1.52f);
  EXPECT_FLOAT_EQ(glass.metallic, 0.0f);
  // Tr when d is absent (Tr = 1 - d); illum 4/6/7/9 is glass even with a texture.
  EXPECT_NEAR(mapped("newmtl pane\nKs 1 1 1\nTr 0.9\nillum 4\n", true).transmission, 0.9f, 1e-6f);
  // d wins over Tr.
  EXPECT_NEAR(mapped("newmtl m\nKs 1 1 1\nd 0.6\nTr 0.9\n").transmission, 0.4f, 1e-6f);
  // No highlight (illum 0/1) or a texture: coverage, blended.
  const AssetMaterial flame = mapped("newmtl flame\nKd 1 0.5 0\nd 0.74\nillum 1\n");
  EXPECT_FLOAT_EQ(flame.transmission, 0.0f);
  EXPECT_FLOAT_EQ(flame.alpha, 0.74f);
  EXPECT_EQ(flame.alpha_mode, AssetAlphaMode::Blend);
  EXPECT_EQ(mapped("newmtl water\nKs 0.5 0.5 0.5\nd 0.5\nmap_Kd w.jpg\n", true).alpha_mode, AssetAlphaMode::Blend);
  // A map_d texture is coverage whatever d says.
  EXPECT_EQ(mapped("newmtl leaf\nKd 1 1 1\nmap_d mask.png\n", false, true).alpha_mode, AssetAlphaMode::Blend);
  // Opaque stays opaque.
  EXPECT_EQ(mapped("newmtl m\nd 1\n").alpha_mode, AssetAlphaMode::Opaque);
}

TEST(AssetMtl, IorDefaultsToGlass) {
  EXPECT_FLOAT_EQ(mapped("newmtl m\nNi 1.000000\n").ior, 1.5f);  // exporters' "not set"
  EXPECT_FLOAT_EQ(mapped("newmtl m\nNi 0\n").ior, 1.5f);
  EXPECT_FLOAT_EQ(mapped("newmtl m\nNi 1.021455\n").ior, 1.5f);  // below any real material
  EXPECT_FLOAT_EQ(mapped("newmtl m\nNi 1.33\n").ior, 1.33f);
  EXPECT_FLOAT_EQ(mapped("newmtl m\nNi 2.42\n").ior, 2.42f);
  EXPECT_FLOAT_EQ(mapped("newmtl m\nNi 3.5\n").ior, 1.5f);  // beyond any optical material here
  EXPECT_FLOAT_EQ(mapped("newmtl m\n").ior, 1.5f);
}

TEST(AssetMtl, SrgbDecodeMatchesTheStandard) {
  const glm::vec3 linear = srgb_colour_to_linear({0.0f, 0.04045f, 1.0f});
  EXPECT_FLOAT_EQ(linear.x, 0.0f);
  EXPECT_NEAR(linear.y, 0.04045f / 12.92f, 1e-8f);
  EXPECT_FLOAT_EQ(linear.z, 1.0f);
  EXPECT_NEAR(srgb_colour_to_linear(glm::vec3(0.5f)).x, 0.21404f, 1e-5f);
}

}  // namespace
}  // namespace phyir::scenes
