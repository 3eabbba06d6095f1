// A furniture piece becomes an insertable glTF object: its triangles, material and texture
// survive the writer and the loader (scenes/asset_gltf.h).
#include <gtest/gtest.h>

#include "insert_test_view.h"
#include "phyir/core/atomic_file.h"
#include "phyir/core/image_io.h"
#include "phyir/scenes/asset_gltf.h"
#include "phyir/scenes/gltf_loader.h"

namespace phyir::insert {
namespace {

using namespace testing;

TEST(AssetObject, ATexturedPieceRoundTripsThroughGltf) {
  const fs::path dir = temp_dir("asset_object");
  Image texels(4, 4, 3, 0.5f);
  write_image(dir / "source.png", texels);
  const std::string png = read_file(dir / "source.png");
  scenes::AssetModel model;
  model.id = "Test#cube";
  model.textures.push_back({"cube.png", std::vector<unsigned char>(png.begin(), png.end()), false});
  scenes::AssetMaterial m;
  m.name = "painted";
  m.base_color_texture = 0;
  m.roughness = 0.7f;
  model.materials.push_back(m);
  scenes::AssetMesh mesh;
  mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}};
  mesh.normals.assign(4, glm::vec3(0, 0, 1));
  mesh.texcoords = {{0, 0}, {1, 0}, {0, 1}, {1, 1}};
  mesh.indices = {0, 1, 2, 2, 1, 3};
  model.meshes.push_back(mesh);
  scenes::AssetEntry entry;
  entry.id = model.id;
  entry.name = "Cube";
  scenes::write_asset_gltf(dir / "cube.gltf", entry, model);
  const scenes::Scene s = scenes::load_gltf(dir / "cube.gltf");
  ASSERT_EQ(s.meshes.size(), 1u);
  EXPECT_EQ(s.triangle_count(), 2u);
  EXPECT_EQ(s.meshes[0].texcoords0.size(), 4u);
  ASSERT_EQ(s.materials.size(), 1u);
  EXPECT_TRUE(s.materials[0].base_color_texture.present());
  EXPECT_NEAR(s.materials[0].roughness_factor, 0.7f, 1e-6f);
  EXPECT_TRUE(fs::exists(dir / "cube_textures" / "0.png"));
}

}  // namespace
}  // namespace phyir::insert
