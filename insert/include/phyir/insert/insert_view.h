#pragma once
// A view as insertion reads it (docs/conventions.md "View folders"): the background colour,
// the first-surface maps that give the world point and material under a pixel, the camera
// centre, and the exposure and display view its PNGs were made with. A dataset view folder or
// a `phyir render` folder; the maps may come from a prediction folder (`phyir infer`).
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <string>

#include <glm/glm.hpp>

#include "phyir/core/image.h"
#include "phyir/render/camera.h"
#include "phyir/view/probe_mosaic.h"

namespace phyir::insert {

// The probe mosaics read for a view, by folder (read_view_probes): a benchmark composites the
// same view under several lightings and seeds, and each mosaic is tens of megabytes.
struct ProbeCache {
  std::mutex mutex;
  std::map<std::filesystem::path, std::shared_ptr<const view::ProbeMosaic>> mosaics;
};

struct InsertView {
  std::filesystem::path dir;
  Image color;                  // linear HDR background (color.exr, or a prediction's panorama)
  Image depth, normal;          // Euclidean distance from the camera; world normal
  Image basecolor, roughness, metalness;
  glm::vec3 camera{0.0f};       // panorama centre, metres
  double exposure_stops = 0.0;  // input.png's (view.json), else color.png's (render.json), else 0
  std::string display_view = "Standard";
  std::shared_ptr<ProbeCache> probe_cache = std::make_shared<ProbeCache>();  // shared by copies
  int width() const { return color.width; }
  int height() const { return color.height; }
};

// The view's own camera: an equirectangular panorama at its centre, at its size.
render::CameraModel panorama_camera(const InsertView& view);

// Reads `dir`: a view folder (color.exr, the camera from view.json or render.json), or a
// `phyir infer` folder (no color.exr, an infer.json: the panorama it names is the background,
// in the predicted probes' unit, the camera at the origin). `maps_dir` (empty: `dir`) holds
// depth, normal and the material maps. Missing or mismatched files: phyir::Error naming the
// file and the problem.
InsertView read_insert_view(const std::filesystem::path& dir, const std::filesystem::path& maps_dir = {});

// What a pixel of the view shows: its world point, normal and material.
struct SurfacePoint {
  glm::vec3 position{0.0f}, normal{0.0f, 1.0f, 0.0f};
  glm::vec3 base_color{0.5f};
  float roughness = 1.0f, metalness = 0.0f;
};

// The surface under pixel (x, y), the world point at the pixel centre: camera + depth x the
// pixel's direction. A pixel outside the image or on no surface (depth 0): phyir::Error.
SurfacePoint surface_at(const InsertView& view, int x, int y);

}  // namespace phyir::insert
