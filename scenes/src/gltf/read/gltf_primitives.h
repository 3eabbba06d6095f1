#pragma once
// A glTF primitive read as stored: in its mesh's local space, attributes validated,
// triangles assembled from its drawing mode.
#include <glm/glm.hpp>

#include <optional>
#include <vector>

#include "gltf/read/gltf_context.h"

namespace phyir::scenes::gltf {

struct PrimitiveData {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;  // empty when the file has none
  std::vector<glm::vec4> tangents;
  std::vector<glm::vec2> texcoords0;
  std::vector<glm::vec2> texcoords1;
  std::vector<glm::vec4> colors;  // COLOR_0 as linear RGBA
  std::vector<glm::uvec3> triangles;
};

// Reads primitive `primitive` of mesh `mesh`. Returns nullopt, after a warning, for a
// primitive that draws no triangles (POINTS, LINES*, or too few indices).
std::optional<PrimitiveData> read_primitive(const GltfContext& ctx, int mesh, int primitive);

// "mesh 0 'Cube' primitive 1": how messages name a primitive.
std::string primitive_label(const GltfContext& ctx, int mesh, int primitive);

// Triangles from a TRIANGLES, TRIANGLE_STRIP or TRIANGLE_FAN index list (glTF 2.0 3.7.2.1).
std::vector<glm::uvec3> assemble_triangles(const std::vector<uint32_t>& indices, int mode);

}  // namespace phyir::scenes::gltf
