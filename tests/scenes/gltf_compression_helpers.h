#pragma once
// For the compression tests: a GLB taken apart (JSON + BIN chunk) so a test can break one
// thing and write it back, and a comparison of two loaded meshes triangle by triangle that
// ignores vertex and triangle order (Draco and meshopt reorder both).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <glm/glm.hpp>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "gltf_test_helpers.h"
#include "phyir/core/atomic_file.h"
#include "phyir/scenes/scene.h"

namespace phyir::scenes::test {

struct GlbParts {
  nlohmann::json doc;
  std::vector<unsigned char> bin;  // the BIN chunk: buffer 0
};

inline uint32_t glb_u32(const std::string& bytes, size_t offset) {
  uint32_t v;
  std::memcpy(&v, bytes.data() + offset, sizeof v);
  return v;
}

inline GlbParts read_glb(const std::filesystem::path& path) {
  const std::string bytes = read_file(path);
  const uint32_t json_length = glb_u32(bytes, 12);
  GlbParts parts;
  parts.doc = nlohmann::json::parse(bytes.substr(20, json_length));
  const size_t bin = 20 + json_length;
  if (bytes.size() >= bin + 8) {
    const uint32_t bin_length = glb_u32(bytes, bin);
    parts.bin.assign(bytes.begin() + static_cast<std::ptrdiff_t>(bin + 8),
                     bytes.begin() + static_cast<std::ptrdiff_t>(bin + 8 + bin_length));
  }
  return parts;
}

// Writes `parts` as dir/name.glb, its buffers as they are in the JSON.
inline std::filesystem::path write_glb(const GlbParts& parts, const std::filesystem::path& dir,
                                       const std::string& name) {
  std::string json_text = parts.doc.dump();
  while (json_text.size() % 4 != 0) json_text.push_back(' ');
  std::vector<unsigned char> chunk = parts.bin;
  while (chunk.size() % 4 != 0) chunk.push_back(0);
  std::string glb;
  auto put_u32 = [&](uint32_t v) { glb.append(reinterpret_cast<const char*>(&v), 4); };
  put_u32(0x46546C67);  // "glTF"
  put_u32(2);
  put_u32(static_cast<uint32_t>(12 + 8 + json_text.size() + (chunk.empty() ? 0 : 8 + chunk.size())));
  put_u32(static_cast<uint32_t>(json_text.size()));
  put_u32(0x4E4F534A);  // "JSON"
  glb += json_text;
  if (!chunk.empty()) {
    put_u32(static_cast<uint32_t>(chunk.size()));
    put_u32(0x004E4942);  // "BIN\0"
    glb.append(reinterpret_cast<const char*>(chunk.data()), chunk.size());
  }
  const std::filesystem::path path = dir / (name + ".glb");
  write_bytes(path, glb.data(), glb.size());
  return path;
}

// The largest differences found between matched triangles.
struct MeshDifference {
  size_t triangles = 0;   // matched
  size_t unmatched = 0;   // variant triangles with no original within the tolerance
  float position = 0.0f;  // world units
  float normal_degrees = 0.0f;
  float tangent_degrees = 0.0f;
  int tangent_sign_flips = 0;  // corners whose handedness w differs
  float uv = 0.0f;             // after dividing the variant's UVs by uv_divisor
};

inline float degrees_between(const glm::vec3& a, const glm::vec3& b) {
  const float c = std::clamp(glm::dot(glm::normalize(a), glm::normalize(b)), -1.0f, 1.0f);
  return glm::degrees(std::acos(c));
}

inline float max_abs(const glm::vec3& d) { return std::max({std::abs(d.x), std::abs(d.y), std::abs(d.z)}); }

// Largest extent of the mesh's bounding box: the quantization grids are fitted to it.
inline float bounding_box_size(const Mesh& mesh) {
  glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
  for (const glm::vec3& p : mesh.positions) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  return max_abs(hi - lo);
}

// Matches each triangle of `variant` to the unused triangle of `original` whose corners
// (in some rotation) are nearest, if within `position_tolerance`, and measures the
// attribute differences at the matched corners.
inline MeshDifference compare_meshes(const Mesh& original, const Mesh& variant, float position_tolerance,
                                     float uv_divisor = 1.0f) {
  MeshDifference diff;
  std::vector<bool> used(original.triangles.size(), false);
  for (const glm::uvec3& v : variant.triangles) {
    size_t best = original.triangles.size();
    int best_rotation = 0;
    float best_error = position_tolerance;
    for (size_t o = 0; o < original.triangles.size(); ++o) {
      if (used[o]) continue;
      for (int r = 0; r < 3; ++r) {
        float error = 0.0f;
        for (int k = 0; k < 3; ++k)
          error = std::max(error, max_abs(variant.positions[v[k]] -
                                          original.positions[original.triangles[o][(k + r) % 3]]));
        if (error <= best_error) {
          best_error = error;
          best = o;
          best_rotation = r;
        }
      }
    }
    if (best == original.triangles.size()) {
      ++diff.unmatched;
      continue;
    }
    used[best] = true;
    ++diff.triangles;
    diff.position = std::max(diff.position, best_error);
    for (int k = 0; k < 3; ++k) {
      const uint32_t a = original.triangles[best][(k + best_rotation) % 3];
      const uint32_t b = v[k];
      diff.normal_degrees =
          std::max(diff.normal_degrees, degrees_between(original.normals[a], variant.normals[b]));
      if (!original.tangents.empty() && !variant.tangents.empty()) {
        diff.tangent_degrees =
            std::max(diff.tangent_degrees,
                     degrees_between(glm::vec3(original.tangents[a]), glm::vec3(variant.tangents[b])));
        if (original.tangents[a].w != variant.tangents[b].w) ++diff.tangent_sign_flips;
      }
      if (!original.texcoords0.empty() && !variant.texcoords0.empty()) {
        const glm::vec2 d = original.texcoords0[a] - variant.texcoords0[b] / uv_divisor;
        diff.uv = std::max({diff.uv, std::abs(d.x), std::abs(d.y)});
      }
    }
  }
  return diff;
}

}  // namespace phyir::scenes::test
