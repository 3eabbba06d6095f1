// corner_normals: given or generated per docs/assets.md ("Normals").
#include "assets/asset_normals.h"

#include <cmath>
#include <cstdint>

#include "phyir/core/safe_math.h"

namespace phyir::scenes {

namespace {

// Java 3D's NormalGenerator as Sweet Home 3D builds it: new NormalGenerator(Math.PI / 2).
constexpr float kCosCreaseAngle = 0.0f;  // cos(90 degrees)

glm::vec3 unit_or(glm::vec3 v, glm::vec3 fallback) {
  const float length2 = glm::dot(v, v);
  return length2 > kMinLength2 ? v / std::sqrt(length2) : fallback;
}

// Triangles around each position (compressed rows: first[p] .. first[p + 1]).
struct Adjacency {
  std::vector<uint32_t> first;
  std::vector<uint32_t> triangles;
};

Adjacency smooth_adjacency(const ObjSoup& soup) {
  Adjacency a;
  a.first.assign(soup.positions.size() + 1, 0);
  for (const ObjTriangle& t : soup.triangles) {
    if (t.smoothing == 0) continue;
    for (const ObjCorner& c : t.corners) ++a.first[static_cast<size_t>(c.position) + 1];
  }
  for (size_t p = 1; p < a.first.size(); ++p) a.first[p] += a.first[p - 1];
  a.triangles.resize(a.first.back());
  std::vector<uint32_t> next(a.first.begin(), a.first.end() - 1);
  for (size_t i = 0; i < soup.triangles.size(); ++i) {
    const ObjTriangle& t = soup.triangles[i];
    if (t.smoothing == 0) continue;
    for (const ObjCorner& c : t.corners) a.triangles[next[static_cast<size_t>(c.position)]++] = static_cast<uint32_t>(i);
  }
  return a;
}

bool has_own_normals(const ObjSoup& soup, const ObjTriangle& t) {
  for (const ObjCorner& c : t.corners) {
    if (c.normal < 0 || glm::dot(soup.normals[static_cast<size_t>(c.normal)], soup.normals[static_cast<size_t>(c.normal)]) == 0.0f) {
      return false;
    }
  }
  return true;
}

// The angle of a triangle at its corner on `position` (0 for a degenerate corner).
float corner_angle(const ObjSoup& soup, const ObjTriangle& t, int position) {
  int k = 0;
  while (k < 2 && t.corners[k].position != position) ++k;
  const glm::vec3 p = soup.positions[static_cast<size_t>(t.corners[k].position)];
  const glm::vec3 a = unit_or(soup.positions[static_cast<size_t>(t.corners[(k + 1) % 3].position)] - p, glm::vec3(0.0f));
  const glm::vec3 b = unit_or(soup.positions[static_cast<size_t>(t.corners[(k + 2) % 3].position)] - p, glm::vec3(0.0f));
  return safe_acos(glm::dot(a, b));
}

// Weighted by each face's angle at the vertex, so the result does not depend on how the
// OBJ's polygons were cut into triangles (area weights would favour the side cut twice).
glm::vec3 smooth_normal(const ObjSoup& soup, const Adjacency& adjacency, const std::vector<glm::vec3>& face_unit,
                        size_t triangle, int position) {
  const unsigned group = soup.triangles[triangle].smoothing;
  const glm::vec3 own = face_unit[triangle];
  glm::vec3 sum(0.0f);
  for (uint32_t k = adjacency.first[static_cast<size_t>(position)]; k < adjacency.first[static_cast<size_t>(position) + 1]; ++k) {
    const uint32_t other = adjacency.triangles[k];
    if (soup.triangles[other].smoothing != group) continue;
    if (glm::dot(own, face_unit[other]) >= kCosCreaseAngle) {
      sum += corner_angle(soup, soup.triangles[other], position) * face_unit[other];
    }
  }
  return unit_or(sum, own);
}

}  // namespace

glm::vec3 area_normal(const ObjSoup& soup, const ObjTriangle& t) {
  const glm::vec3 a = soup.positions[static_cast<size_t>(t.corners[0].position)];
  const glm::vec3 b = soup.positions[static_cast<size_t>(t.corners[1].position)];
  const glm::vec3 c = soup.positions[static_cast<size_t>(t.corners[2].position)];
  return glm::cross(b - a, c - a);
}

std::vector<glm::vec3> corner_normals(const ObjSoup& soup) {
  std::vector<glm::vec3> face(soup.triangles.size());  // unit; zero for a degenerate triangle
  for (size_t i = 0; i < face.size(); ++i) face[i] = unit_or(area_normal(soup, soup.triangles[i]), glm::vec3(0.0f));
  const Adjacency adjacency = smooth_adjacency(soup);
  std::vector<glm::vec3> normals(3 * soup.triangles.size());
  for (size_t i = 0; i < soup.triangles.size(); ++i) {
    const ObjTriangle& t = soup.triangles[i];
    const bool own = has_own_normals(soup, t);
    const glm::vec3 flat = face[i];
    for (int k = 0; k < 3; ++k) {
      glm::vec3& n = normals[3 * i + static_cast<size_t>(k)];
      if (own) {
        n = soup.normals[static_cast<size_t>(t.corners[k].normal)];
      } else {
        n = t.smoothing == 0 ? flat : smooth_normal(soup, adjacency, face, i, t.corners[k].position);
      }
    }
  }
  return normals;
}

}  // namespace phyir::scenes

