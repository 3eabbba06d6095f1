#pragma once
// `phyir insert` as a library call: an object into a view, rendered with the local scene under
// the chosen lighting and composited differentially (docs/insert.md).
#include <cstdint>
#include <filesystem>

#include <nlohmann/json.hpp>

#include "phyir/insert/differential_composite.h"
#include "phyir/insert/insert_lighting.h"
#include "phyir/insert/insert_view.h"
#include "phyir/insert/local_scene.h"
#include "phyir/scenes/scene.h"

namespace phyir::insert {

struct InsertRequest {
  int x = 0, y = 0;  // the pixel the object stands on
  Placement placement;
  LightingRequest lighting;
  // Only the pixels the local scene covers are path traced, so spp costs little next to the
  // fixed work (docs/insert.md "Samples per pixel": 16 -> 256 spp is +35% time).
  int spp = 256;
  int max_bounces = 4;
  uint64_t seed = 1;
};

struct InsertResult {
  Composite composite;
  LocalRender with_object, without_object;
  SurfacePoint ground;
  nlohmann::json record;  // insert.json, less the output file list
};

// `object`: as loaded (scenes::load_gltf). Same seed, same result for any thread count.
InsertResult insert_object(const InsertView& view, const scenes::Scene& object, const InsertRequest& request);

// Writes composite.exr, composite.png (the view's exposure and display view), mask.png and
// insert.json (last) into `out`, each under a temporary name, then renamed.
void write_insert_outputs(const std::filesystem::path& out, const InsertView& view, const InsertResult& result);

}  // namespace phyir::insert
