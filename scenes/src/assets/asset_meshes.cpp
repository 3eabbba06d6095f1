// build_meshes: vertex welding per material.
#include "assets/asset_meshes.h"

#include <unordered_map>
#include <unordered_set>

#include "assets/asset_normals.h"
#include "phyir/scenes/triangle_corners.h"

namespace phyir::scenes {

namespace {

// Twice the area below which a triangle is degenerate: (0.1 um)^2, far below any modelled
// detail of furniture, above float round-off of collinear corners.
constexpr float kDegenerateArea2 = 1e-14f;

// Normals closer than this weld: coplanar triangles of one polygon get flat normals that
// differ in the last bits (each is its own cross product), 1e-5 rad is far below shading.
constexpr float kNormalWeldStep = 1e-5f;

struct VertexKey {
  int position;
  int texcoord;
  glm::ivec3 normal;  // quantised by kNormalWeldStep
  bool operator==(const VertexKey& o) const {
    return position == o.position && texcoord == o.texcoord && normal == o.normal;
  }
};

struct VertexKeyHash {
  size_t operator()(const VertexKey& k) const {
    size_t h = std::hash<int>()(k.position) * 0x9E3779B97F4A7C15ull ^ std::hash<int>()(k.texcoord);
    for (int i = 0; i < 3; ++i) h = h * 31 + static_cast<size_t>(k.normal[i]);
    return h;
  }
};

glm::ivec3 quantised(glm::vec3 n) { return glm::ivec3(glm::round(n / kNormalWeldStep)); }

class MeshWelder {
 public:
  MeshWelder(const ObjSoup& soup, int material) : soup_(soup) { mesh_.material = material; }

  void add_corner(const ObjCorner& corner, glm::vec3 normal) {
    const VertexKey key{corner.position, corner.texcoord, quantised(normal)};
    const auto [it, inserted] = index_of_.emplace(key, static_cast<uint32_t>(mesh_.positions.size()));
    if (inserted) {
      mesh_.positions.push_back(soup_.positions[static_cast<size_t>(corner.position)]);
      mesh_.normals.push_back(normal);
      const glm::vec2 uv = corner.texcoord >= 0 ? soup_.texcoords[static_cast<size_t>(corner.texcoord)] : glm::vec2(0.0f);
      mesh_.texcoords.push_back({uv.x, 1.0f - uv.y});
      has_texcoords_ = has_texcoords_ || corner.texcoord >= 0;
    }
    mesh_.indices.push_back(it->second);
  }

  AssetMesh finish() {
    if (!has_texcoords_) mesh_.texcoords.clear();
    return std::move(mesh_);
  }
  bool empty() const { return mesh_.indices.empty(); }

 private:
  const ObjSoup& soup_;
  AssetMesh mesh_;
  std::unordered_map<VertexKey, uint32_t, VertexKeyHash> index_of_;
  bool has_texcoords_ = false;
};

}  // namespace

std::vector<AssetMesh> build_meshes(const ObjSoup& soup, std::vector<std::string>& warnings) {
  const std::vector<glm::vec3> normals = corner_normals(soup);
  std::vector<MeshWelder> welders;
  welders.reserve(soup.materials.size());
  for (size_t m = 0; m < soup.materials.size(); ++m) welders.emplace_back(soup, static_cast<int>(m));
  // Every material is double-sided (asset_material.h), so a coincident twin of a triangle
  // in the same material adds nothing but a tie for which of the two a ray hits.
  std::vector<std::unordered_set<TriangleCorners, TriangleCornersHash>> seen(soup.materials.size());
  size_t degenerate = 0;
  for (size_t i = 0; i < soup.triangles.size(); ++i) {
    const ObjTriangle& t = soup.triangles[i];
    const glm::vec3 n = area_normal(soup, t);
    if (!(glm::dot(n, n) > kDegenerateArea2 * kDegenerateArea2)) {
      ++degenerate;
      continue;
    }
    const auto corner = [&](int k) { return soup.positions[static_cast<size_t>(t.corners[k].position)]; };
    if (!seen[static_cast<size_t>(t.material)].insert(TriangleCorners(corner(0), corner(1), corner(2))).second) continue;
    for (int k = 0; k < 3; ++k) welders[static_cast<size_t>(t.material)].add_corner(t.corners[k], normals[3 * i + static_cast<size_t>(k)]);
  }
  if (degenerate > 0) warnings.push_back(std::to_string(degenerate) + " zero-area triangles dropped");
  std::vector<AssetMesh> meshes;
  for (MeshWelder& welder : welders) {
    if (!welder.empty()) meshes.push_back(welder.finish());
  }
  return meshes;
}

}  // namespace phyir::scenes
