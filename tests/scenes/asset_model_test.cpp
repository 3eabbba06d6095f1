// load_model on the fixture models: normalisation to the catalog box (after modelRotation),
// the front towards +Z, normals (given, flat, smooth), glTF texture coordinates, textures
// extracted from the archive, materials; and broken models giving clear errors or warnings.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>

#include "phyir/core/error.h"
#include "phyir/scenes/asset_library.h"

namespace phyir::scenes {
namespace {

namespace fs = std::filesystem;

const fs::path kAssets = fs::path(PHYIR_TEST_DATA_DIR) / "assets";

const AssetLibrary& fixture() {
  static const AssetLibrary library = AssetLibrary::open(kAssets / "fixture" / "PhyirFixture.sh3f");
  return library;
}

// Bounding box against the catalog box: 1e-4 m (0.1 mm), float positions are good to ~1e-7.
constexpr float kBoxTolerance = 1e-4f;

void expect_catalog_box(const AssetModel& model, glm::vec3 size) {
  const glm::vec3 lo = model.bounds_min(), hi = model.bounds_max();
  for (int axis = 0; axis < 3; ++axis) {
    EXPECT_NEAR(hi[axis] - lo[axis], size[axis], kBoxTolerance) << "axis " << axis;
  }
  EXPECT_NEAR(lo.x, -0.5f * size.x, kBoxTolerance);
  EXPECT_NEAR(lo.y, 0.0f, kBoxTolerance);
  EXPECT_NEAR(lo.z, -0.5f * size.z, kBoxTolerance);
}

const AssetMaterial& material(const AssetModel& model, const std::string& name) {
  const auto it = std::find_if(model.materials.begin(), model.materials.end(),
                               [&](const AssetMaterial& m) { return m.name == name; });
  EXPECT_NE(it, model.materials.end()) << name;
  return *it;
}

const AssetMesh& mesh_of(const AssetModel& model, const std::string& material_name) {
  for (const AssetMesh& mesh : model.meshes) {
    if (model.materials[static_cast<size_t>(mesh.material)].name == material_name) return mesh;
  }
  ADD_FAILURE() << "no mesh of material " << material_name;
  return model.meshes.front();
}

TEST(AssetModel, EveryFixtureModelFillsItsCatalogBox) {
  for (const AssetEntry& entry : fixture().entries()) {
    SCOPED_TRACE(entry.id);
    const AssetModel model = load_model(entry);
    EXPECT_EQ(model.id, entry.id);
    EXPECT_GT(model.triangle_count(), 0u);
    expect_catalog_box(model, entry.size_m);
    for (const AssetMesh& mesh : model.meshes) {
      ASSERT_EQ(mesh.normals.size(), mesh.positions.size());
      for (const glm::vec3& n : mesh.normals) EXPECT_NEAR(glm::length(n), 1.0f, 1e-5f);
      for (uint32_t i : mesh.indices) ASSERT_LT(i, mesh.positions.size());
    }
  }
}

// Triangles wind counter-clockwise seen from the side their normal faces.
void expect_normals_agree_with_winding(const AssetMesh& mesh) {
  for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
    const glm::vec3 a = mesh.positions[mesh.indices[t]], b = mesh.positions[mesh.indices[t + 1]],
                    c = mesh.positions[mesh.indices[t + 2]];
    const glm::vec3 face = glm::cross(b - a, c - a);
    EXPECT_GT(glm::dot(face, mesh.normals[mesh.indices[t]]), 0.0f);
  }
}

TEST(AssetModel, ChairIsRotatedUprightWithItsBackAtMinusZ) {
  // Authored Z-up with the back at +Y; modelRotation rows (1 0 0)(0 0 1)(0 -1 0) stand it up
  // and turn its front to +Z, as Sweet Home 3D shows it.
  const AssetModel chair = load_model(fixture().at("PhyIR#chair"));
  const AssetMesh& fabric = mesh_of(chair, "fabric");
  float back_z = 1.0f;  // the backrest: the fabric above the seat (seat top at 45 of 90 units)
  for (const glm::vec3& p : fabric.positions) {
    if (p.y > 0.6f) back_z = std::min(back_z, p.z);
  }
  EXPECT_NEAR(back_z, -0.25f, kBoxTolerance);
  for (const glm::vec3& p : fabric.positions) {
    if (p.y > 0.6f) {
      EXPECT_LT(p.z, -0.2f);  // the whole backrest is behind
    }
  }
  // Given normals are rotated with the model: the seat top faces +Y.
  bool seat_top_up = false;
  for (size_t i = 0; i < fabric.positions.size(); ++i) {
    if (std::abs(fabric.positions[i].y - 0.4625f) < 1e-3f && fabric.normals[i].y > 0.999f) seat_top_up = true;
  }
  EXPECT_TRUE(seat_top_up);
  expect_normals_agree_with_winding(fabric);
}

TEST(AssetModel, NormalsAreFlatWithoutSmoothingAndSmoothWithin) {
  // The table has no normals and no "s": every normal is a box face's axis.
  const AssetModel table = load_model(fixture().at("PhyIR#table"));
  for (const glm::vec3& n : table.meshes[0].normals) {
    EXPECT_NEAR(std::max({std::abs(n.x), std::abs(n.y), std::abs(n.z)}), 1.0f, 1e-5f);
  }
  expect_normals_agree_with_winding(table.meshes[0]);
  // The lamp's cylinder (s 1, no normals) is smooth: horizontal radial normals, not the 12
  // facet normals; its caps (s off) are flat.
  const AssetModel lamp = load_model(fixture().at("PhyIR#lamp"));
  const AssetMesh& brass = mesh_of(lamp, "brass");
  size_t radial = 0, caps = 0;
  for (size_t i = 0; i < brass.positions.size(); ++i) {
    const glm::vec3 p = brass.positions[i], n = brass.normals[i];
    if (p.y > 0.041f || std::hypot(p.x, p.z) < 0.059f) continue;  // the base's rims (radius 6 cm, 4 cm high)
    if (std::abs(n.y) > 0.999f) {
      ++caps;
    } else {
      const glm::vec3 outward = glm::normalize(glm::vec3(p.x, 0.0f, p.z));
      EXPECT_NEAR(glm::dot(n, outward), 1.0f, 1e-5f);
      ++radial;
    }
  }
  EXPECT_EQ(radial, 24u);  // 12 segments x 2 rings, each welded once
  EXPECT_EQ(caps, 24u);
  expect_normals_agree_with_winding(brass);
}

TEST(AssetModel, TexturesComeFromTheArchiveWithGltfCoordinates) {
  // table.mtl names "C:\Users\artist\My Textures\Wood.PNG": found by its file name, any case.
  const AssetModel table = load_model(fixture().at("PhyIR#table"));
  ASSERT_EQ(table.textures.size(), 1u);
  EXPECT_EQ(table.textures[0].name, "fixture/table/wood.png");
  ASSERT_GT(table.textures[0].bytes.size(), 8u);
  EXPECT_EQ(std::memcmp(table.textures[0].bytes.data(), "\x89PNG", 4), 0);
  EXPECT_FALSE(table.textures[0].has_alpha);
  const AssetMaterial& wood = material(table, "wood");
  EXPECT_EQ(wood.base_color_texture, 0);
  EXPECT_EQ(wood.base_color, glm::vec3(1.0f));
  EXPECT_EQ(wood.alpha_mode, AssetAlphaMode::Opaque);
  EXPECT_TRUE(table.warnings.empty());
  // The plant's leaves: OBJ vt (0,0) at the bottom becomes glTF (0,1); an RGBA PNG is a cut-out.
  const AssetModel plant = load_model(fixture().at("PhyIR#plant"));
  const AssetMesh& leaf = mesh_of(plant, "leaf");
  ASSERT_EQ(leaf.texcoords.size(), leaf.positions.size());
  for (size_t i = 0; i < leaf.positions.size(); ++i) {
    EXPECT_NEAR(leaf.texcoords[i].y, leaf.positions[i].y < 0.1f ? 1.0f : 0.0f, 1e-6f);
  }
  const AssetMaterial& leaf_material = material(plant, "leaf");
  ASSERT_GE(leaf_material.base_color_texture, 0);
  EXPECT_TRUE(plant.textures[static_cast<size_t>(leaf_material.base_color_texture)].has_alpha);
  EXPECT_EQ(leaf_material.alpha_mode, AssetAlphaMode::Mask);
  EXPECT_TRUE(mesh_of(plant, "pot").texcoords.empty());  // no vt: no coordinates
}

TEST(AssetModel, FixtureMaterialsFollowTheMapping) {
  const AssetModel lamp = load_model(fixture().at("PhyIR#lamp"));
  EXPECT_FLOAT_EQ(material(lamp, "brass").metallic, 1.0f);     // coloured Ks over weak Kd
  EXPECT_NEAR(material(lamp, "glass").transmission, 0.7f, 1e-6f);  // d 0.3
  const AssetModel chair = load_model(fixture().at("PhyIR#chair"));
  EXPECT_FLOAT_EQ(material(chair, "steel").metallic, 1.0f);    // Pm
  EXPECT_FLOAT_EQ(material(chair, "steel").roughness, 0.3f);   // Pr
  const AssetModel window = load_model(fixture().at("PhyIR#window"));
  EXPECT_NEAR(material(window, "pane").transmission, 0.9f, 1e-6f);  // Tr 0.9, illum 4
  EXPECT_FLOAT_EQ(material(window, "pane").ior, 1.52f);
  const AssetModel plant = load_model(fixture().at("PhyIR#plant"));
  EXPECT_FLOAT_EQ(material(plant, "pot").roughness, 1.0f);    // illum 1
}

std::string load_error(const AssetEntry& entry) {
  try {
    load_model(entry);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

bool has_warning(const AssetModel& model, const std::string& part) {
  return std::any_of(model.warnings.begin(), model.warnings.end(),
                     [&](const std::string& w) { return w.find(part) != std::string::npos; });
}

TEST(AssetModel, BrokenModelsFailOrWarnClearly) {
  const fs::path archive = kAssets / "broken" / "broken_models.sh3f";
  const AssetLibrary library = AssetLibrary::open(archive);
  EXPECT_EQ(load_error(library.at("Broken#lines")),
            archive.string() + ": m/lines.obj (entry 'Broken#lines'): no triangles (only points or lines, or every "
                               "face invalid)");
  // A face with an index past the vertices is dropped; the rest loads.
  const AssetModel indices = load_model(library.at("Broken#indices"));
  EXPECT_EQ(indices.triangle_count(), 2u);
  EXPECT_TRUE(has_warning(indices, "1 faces dropped")) << (indices.warnings.empty() ? "" : indices.warnings[0]);
  // A missing MTL: the default (white) material.
  const AssetModel no_mtl = load_model(library.at("Broken#nomtl"));
  EXPECT_TRUE(has_warning(no_mtl, "MTL file 'm/absent.mtl' is not in the archive"));
  ASSERT_EQ(no_mtl.materials.size(), 1u);
  EXPECT_EQ(no_mtl.materials[0].name, "(default)");
  EXPECT_EQ(no_mtl.materials[0].base_color, glm::vec3(1.0f));
  // A missing texture: Kd stays, a warning names the file.
  const AssetModel no_texture = load_model(library.at("Broken#notexture"));
  EXPECT_TRUE(has_warning(no_texture, "map_Kd 'missing.jpg' not in the archive: Kd used"));
  EXPECT_EQ(no_texture.materials[0].base_color_texture, -1);
  EXPECT_NEAR(no_texture.materials[0].base_color.x, 0.214f, 1e-3f);
  // An entry whose archive disappeared after the catalog was read.
  AssetEntry moved = library.at("Broken#indices");
  moved.archive = kAssets / "broken" / "moved.sh3f";
  EXPECT_EQ(load_error(moved), moved.archive.string() + ": no such file");
}

// A sheet made double-sided by a copy of each triangle wound the other way loads as one
// sheet (every material is double-sided); a copy in another material stays.
TEST(AssetModel, TwinTrianglesOfOneMaterialAreDropped) {
  const AssetLibrary library = AssetLibrary::open(kAssets / "broken" / "broken_models.sh3f");
  const AssetModel twins = load_model(library.at("Broken#twins"));
  EXPECT_FALSE(has_warning(twins, "dropped"));  // a way of modelling, not a fault
  ASSERT_EQ(twins.meshes.size(), 2u);
  EXPECT_EQ(twins.meshes[0].indices.size(), 6u);  // material a: the quad once
  EXPECT_EQ(twins.meshes[1].indices.size(), 3u);  // material b: its own triangle
  EXPECT_EQ(twins.triangle_count(), 3u);
}

}  // namespace
}  // namespace phyir::scenes
