#include "gltf/read/gltf_geometry.h"

#include <cmath>
#include <limits>
#include <utility>

#include "phyir/core/safe_math.h"

namespace phyir::scenes::gltf {

namespace {

// Matrix of cofactors: det(M) * inverse(M)^T without the division, so it stays defined
// for singular (zero-scale) transforms. Times sign(det) it maps normals like the
// inverse transpose up to a positive factor, which the renormalisation removes.
glm::dmat3 cofactor(const glm::dmat3& m) {
  return glm::dmat3(glm::cross(m[1], m[2]), glm::cross(m[2], m[0]), glm::cross(m[0], m[1]));
}

// double -> float without undefined behaviour: a finite double beyond float's range (a
// hostile transform such as scale 1e300) becomes +-infinity, which the loader then reports.
float to_float(double x) {
  if (std::abs(x) <= static_cast<double>(std::numeric_limits<float>::max()) || std::isnan(x))
    return static_cast<float>(x);
  return std::copysign(std::numeric_limits<float>::infinity(), static_cast<float>(x > 0.0 ? 1.0 : -1.0));
}

glm::vec3 to_vec3(const glm::dvec3& v) { return glm::vec3(to_float(v.x), to_float(v.y), to_float(v.z)); }

template <typename T>
std::vector<T> unshare(const std::vector<T>& attribute, const std::vector<glm::uvec3>& triangles) {
  if (attribute.empty()) return {};
  std::vector<T> out;
  out.reserve(triangles.size() * 3);
  for (const glm::uvec3& t : triangles)
    for (int k = 0; k < 3; ++k) out.push_back(attribute[t[k]]);
  return out;
}

}  // namespace

Mesh bake_to_world(const PrimitiveData& local, const glm::dmat4& world) {
  const glm::dmat3 linear(world);
  const double det = glm::determinant(linear);
  const bool mirrored = det < 0.0;
  const glm::dmat3 normal_matrix = cofactor(linear) * (mirrored ? -1.0 : 1.0);

  Mesh mesh;
  mesh.positions.reserve(local.positions.size());
  for (const glm::vec3& p : local.positions) mesh.positions.push_back(to_vec3(glm::dvec3(world * glm::dvec4(p, 1.0))));
  mesh.normals.reserve(local.normals.size());
  for (const glm::vec3& n : local.normals)
    mesh.normals.push_back(
        safe_normalize(to_vec3(normal_matrix * glm::dvec3(n)), glm::vec3(0.0f, 0.0f, 1.0f)));
  // Without file normals the file's tangents must be ignored (glTF 2.0 3.7.2.1).
  if (!local.normals.empty()) {
    mesh.tangents.reserve(local.tangents.size());
    for (const glm::vec4& t : local.tangents) {
      const glm::vec3 xyz = safe_normalize(to_vec3(linear * glm::dvec3(t)), glm::vec3(1.0f, 0.0f, 0.0f));
      mesh.tangents.emplace_back(xyz, mirrored ? -t.w : t.w);
    }
  }
  mesh.texcoords0 = local.texcoords0;
  mesh.texcoords1 = local.texcoords1;
  mesh.colors = local.colors;
  mesh.triangles = local.triangles;
  if (mirrored)
    for (glm::uvec3& t : mesh.triangles) std::swap(t.y, t.z);
  if (mesh.normals.empty()) make_flat_normals(mesh);
  return mesh;
}

void make_flat_normals(Mesh& mesh) {
  const std::vector<glm::uvec3> triangles = mesh.triangles;
  mesh.positions = unshare(mesh.positions, triangles);
  mesh.tangents = unshare(mesh.tangents, triangles);
  mesh.texcoords0 = unshare(mesh.texcoords0, triangles);
  mesh.texcoords1 = unshare(mesh.texcoords1, triangles);
  mesh.colors = unshare(mesh.colors, triangles);
  mesh.normals.clear();
  mesh.normals.reserve(mesh.positions.size());
  for (size_t t = 0; t < triangles.size(); ++t) {
    const glm::vec3* p = &mesh.positions[3 * t];
    // Counter-clockwise winding faces the normal (the convention in scene.h).
    const glm::vec3 n = safe_normalize(glm::cross(p[1] - p[0], p[2] - p[0]), glm::vec3(0.0f, 0.0f, 1.0f));
    mesh.normals.insert(mesh.normals.end(), 3, n);
    const auto first = static_cast<uint32_t>(3 * t);
    mesh.triangles[t] = glm::uvec3(first, first + 1, first + 2);
  }
}

bool generate_tangents(Mesh& mesh, int texcoord) {
  const std::vector<glm::vec2>& uv = texcoord == 1 ? mesh.texcoords1 : mesh.texcoords0;
  if (uv.size() != mesh.positions.size() || mesh.normals.size() != mesh.positions.size()) return false;
  std::vector<glm::vec3> dp_du(mesh.positions.size(), glm::vec3(0.0f));
  std::vector<glm::vec3> dp_dv(mesh.positions.size(), glm::vec3(0.0f));
  for (const glm::uvec3& t : mesh.triangles) {
    const glm::vec3 e1 = mesh.positions[t.y] - mesh.positions[t.x];
    const glm::vec3 e2 = mesh.positions[t.z] - mesh.positions[t.x];
    const glm::vec2 d1 = uv[t.y] - uv[t.x];
    const glm::vec2 d2 = uv[t.z] - uv[t.x];
    // Solve [e1 e2] = [dP/du dP/dv] [d1 d2]; a degenerate UV triangle contributes nothing.
    const float r = safe_div(1.0f, d1.x * d2.y - d2.x * d1.y);
    const glm::vec3 su = (e1 * d2.y - e2 * d1.y) * r;
    const glm::vec3 sv = (e2 * d1.x - e1 * d2.x) * r;
    for (int k = 0; k < 3; ++k) {
      dp_du[t[k]] += su;
      dp_dv[t[k]] += sv;
    }
  }
  mesh.tangents.resize(mesh.positions.size());
  for (size_t i = 0; i < mesh.positions.size(); ++i) {
    const glm::vec3& n = mesh.normals[i];
    const glm::vec3 any_perpendicular = std::abs(n.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
    const glm::vec3 fallback = glm::normalize(glm::cross(n, glm::cross(any_perpendicular, n)));
    const glm::vec3 t = safe_normalize(dp_du[i] - n * glm::dot(n, dp_du[i]), fallback);
    // glTF's v grows downwards in the image, so "up" is -dP/dv.
    const float w = glm::dot(glm::cross(n, t), -dp_dv[i]) < 0.0f ? -1.0f : 1.0f;
    mesh.tangents[i] = glm::vec4(t, w);
  }
  return true;
}

}  // namespace phyir::scenes::gltf
