#pragma once
// A synthetic view for the insertion tests: a camera 1 m above an infinite grey floor (y = 0)
// under nothing, written as a view folder (color.exr, the maps, render.json, probes), and a
// unit box object built in memory.
#include <unistd.h>

#include <filesystem>
#include <string>

#include <glm/glm.hpp>

#include "phyir/core/atomic_file.h"
#include "phyir/core/equirect.h"
#include "phyir/core/image_io.h"
#include "phyir/scenes/scene.h"
#include "phyir/view/probe_mosaic.h"

namespace phyir::insert::testing {

namespace fs = std::filesystem;

inline const glm::vec3 kCamera(0.0f, 1.0f, 0.0f);

// Probe (i, j)'s radiance, the same from every direction.
using ProbeRadiance = glm::vec3 (*)(int i, int j);
inline glm::vec3 uniform_light(int, int) { return glm::vec3(1.0f); }

inline fs::path temp_dir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("phyir_insert_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

inline view::ProbeMosaic make_probes(int grid_h, int grid_w, ProbeRadiance light) {
  view::ProbeMosaic p;
  p.layout = view::ProbeLayout{grid_h, grid_w, 4, 8};
  p.radiance = Image(p.layout.mosaic_width(), p.layout.mosaic_height(), 3);
  p.mask = Image(grid_w, grid_h, 1, 1.0f);
  for (int y = 0; y < p.radiance.height; ++y)
    for (int x = 0; x < p.radiance.width; ++x) {
      const glm::vec3 L = light(y / p.layout.res_height, x / p.layout.res_width);
      for (int c = 0; c < 3; ++c) p.radiance.at(x, y, c) = L[c];
    }
  return p;
}

// Writes the floor view (width x 2 width/... as given) with its probes into `dir`.
inline void write_floor_view(const fs::path& dir, int width, int height, const view::ProbeMosaic& probes) {
  Image color(width, height, 3), depth(width, height, 1), normal(width, height, 3), base(width, height, 3);
  Image rough(width, height, 1, 1.0f), metal(width, height, 1, 0.0f);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const glm::vec3 d = equirect_direction(glm::vec2((x + 0.5f) / width, (y + 0.5f) / height));
      // A background with structure, so an untouched pixel is recognisably the same.
      for (int c = 0; c < 3; ++c) color.at(x, y, c) = 0.1f + 0.01f * float((x * 7 + y * 3 + c) % 13);
      if (d.y > -1e-3f) continue;
      depth.at(x, y) = -kCamera.y / d.y;
      normal.at(x, y, 1) = 1.0f;
      for (int c = 0; c < 3; ++c) base.at(x, y, c) = 0.5f;
    }
  write_image(dir / "color.exr", color);
  write_image(dir / "depth.exr", depth);
  write_image(dir / "normal.exr", normal);
  write_image(dir / "basecolor.exr", base);
  write_image(dir / "roughness.exr", rough);
  write_image(dir / "metalness.exr", metal);
  write_file_atomic(dir / "render.json", R"({"camera": {"position": [0, 1, 0]}, "color_png": {"exposure_stops": 0}})");
  view::write_probe_mosaic(dir, probes);
}

// An axis-aligned box from (-h, 0, -h) to (h, 2h, h), outward normals, one grey diffuse material.
inline scenes::Scene box_object(float h) {
  scenes::Scene s;
  s.source = "test box";
  scenes::Material m;
  m.base_color_factor = glm::vec4(0.8f, 0.8f, 0.8f, 1.0f);
  m.metallic_factor = 0.0f;
  m.roughness_factor = 1.0f;
  s.materials.push_back(m);
  scenes::Mesh mesh;
  mesh.name = "box";
  const glm::vec3 lo(-h, 0.0f, -h), hi(h, 2 * h, h);
  for (int axis = 0; axis < 3; ++axis)
    for (int side = 0; side < 2; ++side) {
      glm::vec3 n(0.0f);
      n[axis] = side ? 1.0f : -1.0f;
      const int a = (axis + 1) % 3, b = (axis + 2) % 3;
      const unsigned base = unsigned(mesh.positions.size());
      for (int k = 0; k < 4; ++k) {
        glm::vec3 p;
        p[axis] = side ? hi[axis] : lo[axis];
        p[a] = (k == 1 || k == 2) ? hi[a] : lo[a];
        p[b] = (k >= 2) ? hi[b] : lo[b];
        mesh.positions.push_back(p);
        mesh.normals.push_back(n);
      }
      // Counter-clockwise seen from outside: (a, b) is right-handed with the axis when side = 1.
      if (side) {
        mesh.triangles.emplace_back(base, base + 1, base + 2);
        mesh.triangles.emplace_back(base, base + 2, base + 3);
      } else {
        mesh.triangles.emplace_back(base, base + 2, base + 1);
        mesh.triangles.emplace_back(base, base + 3, base + 2);
      }
    }
  s.meshes.push_back(mesh);
  s.bounds = s.compute_bounds();
  return s;
}

}  // namespace phyir::insert::testing
