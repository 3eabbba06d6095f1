// Do two placed pieces' meshes cross? Two triangle meshes intersect exactly when an edge of
// a triangle of one passes through a triangle of the other (coplanar touching aside), so
// every edge of each piece that lies in the two boxes' overlap is traced, as a segment,
// against the other piece's triangles with Embree.
#include <embree3/rtcore.h>

#include <cmath>
#include <limits>

#include "phyir/core/error.h"
#include "phyir/scenes/apartment_furnishing.h"

namespace phyir::scenes {

namespace {

// Segments shorter than this at each end are not traced: pieces that only touch (a vase on
// a table) must not count as crossing.
constexpr float kContactTolerance = 1e-3f;

RTCDevice shared_device() {
  static RTCDevice device = [] {
    RTCDevice d = rtcNewDevice("threads=1");
    if (!d) fail("apartment: Embree device could not be created (error {})", int(rtcGetDeviceError(nullptr)));
    return d;
  }();
  return device;
}

struct WorldTriangles {
  std::vector<glm::vec3> positions;  // three per triangle
};

WorldTriangles triangles_in(const PlacedAsset& piece, AssetModelCache& models, const Box3& region) {
  const AssetModel& model = models.get(*piece.entry);
  const glm::mat4 m = piece.model_to_world();
  WorldTriangles out;
  for (const AssetMesh& mesh : model.meshes)
    for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
      glm::vec3 p[3];
      Box3 box{glm::vec3(std::numeric_limits<float>::max()), glm::vec3(-std::numeric_limits<float>::max())};
      for (int k = 0; k < 3; ++k) {
        p[k] = glm::vec3(m * glm::vec4(mesh.positions[mesh.indices[t + k]], 1.0f));
        box.min = glm::min(box.min, p[k]);
        box.max = glm::max(box.max, p[k]);
      }
      if (!box.overlaps(region, 0.0f)) continue;
      out.positions.insert(out.positions.end(), p, p + 3);
    }
  return out;
}

class TriangleScene {
 public:
  explicit TriangleScene(const WorldTriangles& tris) : scene_(rtcNewScene(shared_device())) {
    const size_t n = tris.positions.size() / 3;
    RTCGeometry geom = rtcNewGeometry(shared_device(), RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* v = static_cast<float*>(
        rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), 3 * n));
    auto* i = static_cast<unsigned*>(
        rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), n));
    for (size_t k = 0; k < 3 * n; ++k) {
      v[3 * k] = tris.positions[k].x, v[3 * k + 1] = tris.positions[k].y, v[3 * k + 2] = tris.positions[k].z;
      i[k] = static_cast<unsigned>(k);
    }
    rtcCommitGeometry(geom);
    rtcAttachGeometry(scene_, geom);
    rtcReleaseGeometry(geom);
    rtcCommitScene(scene_);
  }
  ~TriangleScene() { rtcReleaseScene(scene_); }
  TriangleScene(const TriangleScene&) = delete;
  TriangleScene& operator=(const TriangleScene&) = delete;

  // True when the segment a -> b (less the contact tolerance at each end) hits a triangle.
  bool segment_hits(const glm::vec3& a, const glm::vec3& b) const {
    const glm::vec3 d = b - a;
    const float length = glm::length(d);
    if (!(length > 2.0f * kContactTolerance)) return false;
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRay ray{};
    ray.org_x = a.x, ray.org_y = a.y, ray.org_z = a.z;
    ray.dir_x = d.x / length, ray.dir_y = d.y / length, ray.dir_z = d.z / length;
    ray.tnear = kContactTolerance;
    ray.tfar = length - kContactTolerance;
    ray.mask = 0xFFFFFFFFu;
    rtcOccluded1(scene_, &context, &ray);
    return ray.tfar < 0.0f;  // Embree sets tfar to -inf on a hit
  }

 private:
  RTCScene scene_;
};

bool any_edge_crosses(const WorldTriangles& edges_of, const WorldTriangles& other) {
  if (edges_of.positions.empty() || other.positions.empty()) return false;
  const TriangleScene scene(other);
  for (size_t t = 0; t < edges_of.positions.size(); t += 3)
    for (int k = 0; k < 3; ++k)
      if (scene.segment_hits(edges_of.positions[t + k], edges_of.positions[t + (k + 1) % 3])) return true;
  return false;
}

}  // namespace

bool pieces_interpenetrate(const PlacedAsset& a, const PlacedAsset& b, AssetModelCache& models) {
  const Box3 ba = a.bounds(), bb = b.bounds();
  if (!ba.overlaps(bb, 0.0f)) return false;
  const Box3 region{glm::max(ba.min, bb.min), glm::min(ba.max, bb.max)};
  const WorldTriangles ta = triangles_in(a, models, region), tb = triangles_in(b, models, region);
  return any_edge_crosses(ta, tb) || any_edge_crosses(tb, ta);
}

}  // namespace phyir::scenes
