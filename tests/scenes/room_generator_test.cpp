// The procedural room generator: plans checked against the rules with independent geometry
// (not the generator's own helpers), files byte-identical per seed, and every generated
// file read back through the glTF loader.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "gltf_test_helpers.h"
#include "phyir/core/atomic_file.h"
#include "phyir/core/error.h"
#include "phyir/scenes/gltf_loader.h"
#include "phyir/scenes/room_generator.h"

namespace phyir::scenes {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

constexpr uint64_t kSeed = 3;
constexpr int kRooms = 25;  // rooms per preset in the property tests

float distance_to_box(const Box3& b, const glm::vec3& p) {
  const glm::vec3 d = glm::max(glm::max(b.min - p, p - b.max), glm::vec3(0.0f));
  return std::sqrt(glm::dot(d, d));
}

float distance_to_segment(glm::vec2 p, glm::vec2 a, glm::vec2 b) {
  const glm::vec2 ab = b - a;
  const float t = std::clamp(glm::dot(p - a, ab) / glm::dot(ab, ab), 0.0f, 1.0f);
  return glm::length(p - (a + t * ab));
}

// Inside the floor polygon: in the bounding rectangle and not in the L's notch.
bool inside_floor(const RoomShell& s, glm::vec2 p) {
  if (std::abs(p.x) > 0.5f * s.width || std::abs(p.y) > 0.5f * s.depth) return false;
  return !(s.l_shaped && p.x > s.notch_min.x && p.y > s.notch_min.y);
}

bool overlap_with_volume(const Box3& a, const Box3& b) {
  for (int k = 0; k < 3; ++k) {
    if (a.max[k] <= b.min[k] || b.max[k] <= a.min[k]) return false;
  }
  return true;
}

std::vector<RoomLayout> plans(RoomPreset preset) {
  std::vector<RoomLayout> out;
  for (int i = 0; i < kRooms; ++i) out.push_back(plan_room(kSeed, i, preset));
  return out;
}

void expect_valid_viewpoint(const RoomLayout& room, const glm::vec3& p, const std::string& what) {
  SCOPED_TRACE(what + " of room " + std::to_string(room.index));
  EXPECT_GE(p.y, 1.2f);
  EXPECT_LE(p.y, 1.8f);
  EXPECT_TRUE(inside_floor(room.shell, {p.x, p.z})) << p.x << ", " << p.z;
  const std::vector<glm::vec2> corners = room.shell.outline();
  for (size_t w = 0; w < corners.size(); ++w) {
    EXPECT_GE(distance_to_segment({p.x, p.z}, corners[w], corners[(w + 1) % corners.size()]), 0.3f) << "wall " << w;
  }
  for (const RoomObject& object : room.objects) {
    EXPECT_GE(distance_to_box(object.bounds, p), 0.3f) << object.name;
  }
  EXPECT_TRUE(is_valid_viewpoint(room, p));
}

std::map<std::string, std::string> read_folder(const fs::path& dir) {
  std::map<std::string, std::string> files;
  for (const auto& entry : fs::directory_iterator(dir)) files[entry.path().filename().string()] = read_file(entry.path());
  return files;
}

TEST(RoomPreset, ParsesThePresets) {
  EXPECT_EQ(parse_room_preset("mini"), RoomPreset::Mini);
  EXPECT_EQ(parse_room_preset("hard"), RoomPreset::Hard);
  EXPECT_EQ(parse_room_preset("diffuse"), RoomPreset::Diffuse);
  EXPECT_STREQ(room_preset_name(RoomPreset::Hard), "hard");
  EXPECT_STREQ(room_preset_name(RoomPreset::Diffuse), "diffuse");
}

TEST(RoomPreset, RejectsUnknownNamesNamingThem) {
  try {
    parse_room_preset("huge");
    FAIL() << "'huge' was accepted";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("'huge'"));
  }
}

TEST(RoomPlan, IsAPureFunctionOfSeedIndexAndPreset) {
  const RoomLayout a = plan_room(kSeed, 4, RoomPreset::Hard);
  const RoomLayout b = plan_room(kSeed, 4, RoomPreset::Hard);
  ASSERT_EQ(a.objects.size(), b.objects.size());
  for (size_t i = 0; i < a.objects.size(); ++i) {
    EXPECT_EQ(a.objects[i].name, b.objects[i].name);
    EXPECT_EQ(a.objects[i].bounds.min, b.objects[i].bounds.min);
    EXPECT_EQ(a.objects[i].bounds.max, b.objects[i].bounds.max);
  }
  EXPECT_EQ(a.candidate_viewpoints, b.candidate_viewpoints);
  EXPECT_NE(plan_room(kSeed + 1, 4, RoomPreset::Hard).shell.width, a.shell.width);
  EXPECT_NE(plan_room(kSeed, 5, RoomPreset::Hard).shell.width, a.shell.width);
}

TEST(RoomPlan, ShellsFollowThePresets) {
  int l_shaped = 0;
  for (const RoomLayout& room : plans(RoomPreset::Hard)) {
    EXPECT_GE(room.shell.height, 2.4f);
    EXPECT_LE(room.shell.height, 3.2f);
    EXPECT_EQ(room.wall_materials.size(), room.shell.outline().size());
    l_shaped += room.shell.l_shaped ? 1 : 0;
  }
  EXPECT_GT(l_shaped, 0) << "no L-shaped hard room in " << kRooms;
  EXPECT_LT(l_shaped, kRooms) << "no rectangular hard room in " << kRooms;
  for (const RoomLayout& room : plans(RoomPreset::Mini)) {
    EXPECT_FALSE(room.shell.l_shaped);
    EXPECT_GE(room.shell.height, 2.4f);
    EXPECT_LE(room.shell.height, 3.2f);
    EXPECT_LE(room.shell.width * room.shell.depth, 4.5f * 4.5f);
  }
}

TEST(RoomPlan, FurnitureStandsOnTheFloorInsideTheWallsWithoutOverlap) {
  for (RoomPreset preset : {RoomPreset::Mini, RoomPreset::Hard}) {
    for (const RoomLayout& room : plans(preset)) {
      SCOPED_TRACE(std::string(room_preset_name(preset)) + " room " + std::to_string(room.index));
      for (size_t i = 0; i < room.objects.size(); ++i) {
        const RoomObject& a = room.objects[i];
        if (a.mount == Mount::Floor) {
          EXPECT_EQ(a.bounds.min.y, 0.0f) << a.name;
        }
        EXPECT_GE(a.bounds.min.y, 0.0f) << a.name;
        EXPECT_LE(a.bounds.max.y, room.shell.height) << a.name;
        // All four footprint corners inside the floor polygon (rectangles: enough for an L).
        for (int c = 0; c < 4; ++c) {
          const glm::vec2 corner(c & 1 ? a.bounds.max.x : a.bounds.min.x, c & 2 ? a.bounds.max.z : a.bounds.min.z);
          EXPECT_TRUE(inside_floor(room.shell, corner)) << a.name << " corner " << c;
        }
        for (size_t j = i + 1; j < room.objects.size(); ++j) {
          EXPECT_FALSE(overlap_with_volume(a.bounds, room.objects[j].bounds)) << a.name << " and " << room.objects[j].name;
        }
      }
    }
  }
}

TEST(RoomPlan, CameraAndCandidateViewpointsAreValid) {
  for (RoomPreset preset : {RoomPreset::Mini, RoomPreset::Hard}) {
    for (const RoomLayout& room : plans(preset)) {
      expect_valid_viewpoint(room, room.camera_position, "camera");
      EXPECT_GE(room.candidate_viewpoints.size(), 8u) << "room " << room.index;
      for (const glm::vec3& p : room.candidate_viewpoints) expect_valid_viewpoint(room, p, "candidate");
    }
  }
}

TEST(RoomPlan, DiffuseRoomsHaveOnlyRoughUntexturedDielectricsAndLights) {
  for (const RoomLayout& room : plans(RoomPreset::Diffuse)) {
    SCOPED_TRACE("diffuse room " + std::to_string(room.index));
    EXPECT_TRUE(room.textures.empty());
    int emitters = 0;
    for (const MaterialSpec& m : room.materials) {
      EXPECT_FALSE(m.textured()) << m.name;
      EXPECT_EQ(m.transmission, 0.0f) << m.name;
      if (m.kind == MaterialKind::Emissive) {
        ++emitters;
        continue;
      }
      EXPECT_EQ(m.kind, MaterialKind::Diffuse) << m.name;
      EXPECT_EQ(m.metallic, 0.0f) << m.name;
      EXPECT_EQ(m.roughness, 1.0f) << m.name;
    }
    EXPECT_GE(emitters, 1);
  }
}

TEST(RoomPlan, HardRoomsHaveEveryMaterialKindAndTheHardCases) {
  for (const RoomLayout& room : plans(RoomPreset::Hard)) {
    SCOPED_TRACE("hard room " + std::to_string(room.index));
    std::set<MaterialKind> kinds;
    for (const MaterialSpec& m : room.materials) kinds.insert(m.kind);
    EXPECT_EQ(kinds.size(), static_cast<size_t>(kMaterialKindCount));

    bool thin = false, small_bright_light = false, metallic_roughness_texture = false;
    for (const MaterialSpec& m : room.materials) {
      metallic_roughness_texture |= m.metallic_roughness_texture >= 0;
      if (m.kind == MaterialKind::Mirror) {
        EXPECT_EQ(m.roughness, 0.0f);
        EXPECT_EQ(m.metallic, 1.0f);
      }
      if (m.kind == MaterialKind::Glass) {
        EXPECT_EQ(m.transmission, 1.0f);
        EXPECT_EQ(m.ior, 1.5f);
      }
      if (m.kind == MaterialKind::Emissive) {
        EXPECT_LE(std::max({m.emissive_factor.x, m.emissive_factor.y, m.emissive_factor.z}), 1.0f);
      }
      if (m.name == "light_panel") {
        const glm::vec3 radiance = m.emissive_factor * m.emissive_strength;
        EXPECT_GE(std::max({radiance.x, radiance.y, radiance.z}), 5.0f);
        EXPECT_LE(std::max({radiance.x, radiance.y, radiance.z}), 50.0f);
      }
    }
    for (const RoomObject& object : room.objects) {
      for (const RoomPart& part : object.parts) {
        const glm::vec3 s = part.bounds.size();
        thin |= part.shape == Shape::Box && std::min({s.x, s.y, s.z}) <= 0.0101f;
        small_bright_light |= part.shape == Shape::Sphere && s.x <= 0.1001f &&
                              room.materials[part.material].emissive_strength >= 100.0f;
      }
    }
    EXPECT_TRUE(thin) << "no part 1 cm thick or thinner";
    EXPECT_TRUE(small_bright_light) << "no 5 cm bright emissive sphere";
    EXPECT_TRUE(metallic_roughness_texture);
  }
}

TEST(RoomGenerator, SameSeedWritesByteIdenticalFiles) {
  const fs::path dir = test::fresh_test_dir();
  const RoomSummary a = generate_room(dir / "a", 2, kSeed, RoomPreset::Hard);
  generate_room(dir / "b", 2, kSeed, RoomPreset::Hard);
  generate_room(dir / "c", 2, kSeed + 1, RoomPreset::Hard);
  const auto files_a = read_folder(dir / "a");
  EXPECT_GE(files_a.size(), 3u);  // .gltf, .bin and at least one texture
  EXPECT_EQ(files_a, read_folder(dir / "b"));
  EXPECT_NE(read_file(dir / "a" / a.file), read_file(dir / "c" / a.file));
}

TEST(RoomGenerator, MiniRoomsAreSmall) {
  const fs::path dir = test::fresh_test_dir();
  for (int i = 0; i < 5; ++i) {
    const RoomSummary s = generate_room(dir, i, kSeed, RoomPreset::Mini);
    EXPECT_LE(s.triangles, 3000u) << s.file;
    EXPECT_EQ(s.emissive_meshes, 1u) << s.file;  // one ceiling light
    EXPECT_EQ(s.cameras, 1u);
    EXPECT_LE(s.textures, 1u);
  }
}

// The file as the renderer sees it: counts match the summary, shell normals face into the
// room, every triangle winds counter-clockwise around its normals, viewpoints survive.
TEST(RoomGenerator, GeneratedFilesLoadBackWithTheSummaryCounts) {
  const fs::path dir = test::fresh_test_dir();
  for (RoomPreset preset : {RoomPreset::Mini, RoomPreset::Hard}) {
    for (int i = 0; i < 3; ++i) {
      const RoomLayout plan = plan_room(kSeed, i, preset);
      const RoomSummary summary = generate_room(dir, i, kSeed, preset);
      SCOPED_TRACE(summary.file + " (" + room_preset_name(preset) + ")");
      const Scene scene = load_gltf(dir / summary.file);
      EXPECT_TRUE(scene.warnings.empty()) << scene.warnings.front();
      EXPECT_EQ(scene.meshes.size(), summary.meshes);
      EXPECT_EQ(scene.triangle_count(), summary.triangles);
      EXPECT_EQ(static_cast<size_t>(scene.info.materials), summary.materials);
      EXPECT_EQ(scene.textures.size(), summary.textures);
      ASSERT_EQ(scene.cameras.size(), 1u);
      EXPECT_EQ(scene.cameras[0].position, plan.camera_position);
      EXPECT_NEAR(scene.cameras[0].yfov, 1.2f, 1e-6f);
      EXPECT_NEAR(scene.cameras[0].forward.y, 0.0f, 1e-6f);  // a level view
      EXPECT_EQ(scene.candidate_viewpoints, plan.candidate_viewpoints);
      size_t emissive = 0;
      for (const Mesh& mesh : scene.meshes) emissive += scene.materials[mesh.material].is_emissive() ? 1 : 0;
      EXPECT_EQ(emissive, summary.emissive_meshes);

      int shell_meshes = 0;
      for (const Mesh& mesh : scene.meshes) {
        for (const glm::vec3& n : mesh.normals) ASSERT_NEAR(glm::length(n), 1.0f, 1e-5f) << mesh.name;
        for (const glm::uvec3& t : mesh.triangles) {
          const glm::vec3 face = glm::cross(mesh.positions[t.y] - mesh.positions[t.x], mesh.positions[t.z] - mesh.positions[t.x]);
          const glm::vec3 normal = mesh.normals[t.x] + mesh.normals[t.y] + mesh.normals[t.z];
          ASSERT_GT(glm::dot(face, normal), 0.0f) << mesh.name << " winds clockwise";
        }
        if (mesh.name == "floor/0") {  // the loader names meshes <glTF mesh>/<primitive>
          ++shell_meshes;
          EXPECT_EQ(mesh.normals[0], glm::vec3(0, 1, 0));
        }
        if (mesh.name == "ceiling/0") {
          ++shell_meshes;
          EXPECT_EQ(mesh.normals[0], glm::vec3(0, -1, 0));
        }
        if (mesh.name.rfind("walls_", 0) == 0) {
          ++shell_meshes;
          for (size_t v = 0; v < mesh.positions.size(); ++v) {
            const glm::vec3 inside = mesh.positions[v] + 0.05f * mesh.normals[v];
            ASSERT_TRUE(inside_floor(plan.shell, {inside.x, inside.z})) << mesh.name << " faces out of the room";
          }
        }
      }
      EXPECT_GE(shell_meshes, 3) << "floor, ceiling and walls not all found by name";
    }
  }
}

}  // namespace
}  // namespace phyir::scenes
