#pragma once
// The light the local scene is rendered under (docs/insert.md "Lighting"):
//   gt         the view's probes.exr, spatially varying (ProbeField)
//   predicted  a prediction folder's probes.exr (`phyir infer`), spatially varying
//   global     one probe for the whole object: the valid probe nearest the placement pixel
//   constant   one colour from every direction: the mean radiance of the view's valid probes
//   FILE       an HDR equirect environment file, the same everywhere
// Spatially varying sources sample directions by the local probes' mean map (the global
// probe's texels in projection mode) and take the radiance from the probes nearest each path
// vertex (render::PositionalRadiance).
#include <filesystem>
#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include "phyir/insert/insert_view.h"
#include "phyir/render/environment_light.h"
#include "phyir/view/probe_mosaic.h"

namespace phyir::insert {

// What the local blend's weights measure (docs/insert.md "Lighting"): each probe's distance to
// the ray looked up (ProbeField::set_ray_distance, with the support plane), to the vertex, or
// between foot points on the support plane (ProbeField::set_blend_plane).
enum class BlendDistance { kRay, kPoint, kFoot };
const char* blend_distance_name(BlendDistance d);

struct LightingRequest {
  std::string source = "gt";            // gt | predicted | global | constant | an HDR file
  std::filesystem::path predicted_dir;  // the prediction folder (predicted)
  // gt: with probe_position.exr, blend the probes within this distance of the placement point
  // (ProbeField::use_neighbourhood); 0, or no positions: project into the panorama instead.
  float neighbourhood_radius = 0.5f;
  // Blend only the probes on the support surface's plane (ProbeField::SupportPlane; needs
  // probe_normal.exr): docs/insert.md says what the blend then estimates.
  bool support_plane_only = false;
  float blend_power = 2.0f;  // ProbeField::set_blend_power
  BlendDistance blend_distance = BlendDistance::kRay;
};

struct Lighting {
  std::unique_ptr<render::EnvironmentLight> environment;
  nlohmann::json record;  // what insert.json says about it
};

// The probes of `dir`, checked against the view: the grid must have the panorama's aspect ratio
// (one probe per block of pixels). Missing or mismatched: phyir::Error naming the file.
// Read once per view and folder (InsertView::probe_cache).
std::shared_ptr<const view::ProbeMosaic> read_view_probes(const std::filesystem::path& dir, const InsertView& view);

// The lighting for an object standing on pixel (x, y) of `view`.
Lighting make_lighting(const LightingRequest& request, const InsertView& view, int x, int y);

}  // namespace phyir::insert
