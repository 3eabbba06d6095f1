// phyir scenes sky: the Preetham clear sky as an equirect EXR, and its sun.
#include <fmt/format.h>

#include <filesystem>
#include <iostream>
#include <memory>
#include <string>

#include "commands.h"
#include "phyir/core/error.h"
#include "phyir/core/image_io.h"
#include "phyir/core/log.h"
#include "phyir/core/safe_math.h"
#include "phyir/scenes/sky.h"

namespace phyir::cli {

namespace {

struct SkyOptions {
  std::string out;
  double turbidity = 3.0;
  double sun_elevation_degrees = 35.0;
  double sun_azimuth_degrees = 0.0;
  double ground_albedo = 0.2;
  int width = 2048;
};

constexpr double kDegrees = 3.14159265358979323846 / 180.0;

// "+ 0.0" turns a negative zero into 0 for printing.
std::string rgb(const glm::dvec3& v) { return fmt::format("({:.4g}, {:.4g}, {:.4g})", v.x + 0.0, v.y + 0.0, v.z + 0.0); }
double luminance_of(const glm::dvec3& v) { return luminance(glm::vec3(v)); }

// What the generator puts in a scene: the light's glTF values and the sky's radiometry.
std::string sky_report(const scenes::PreethamSky& sky, const std::string& out, int width) {
  const scenes::GltfLight sun = scenes::sun_light(sky);
  const glm::dvec3 E = sky.sun_irradiance();
  std::string text = fmt::format("sky: {} ({}x{}, linear Rec.709 radiance in W/(sr m^2) at 683 lm/W)\n", out, width,
                                 width / 2);
  text += fmt::format("sun direction (towards the sun): {}\n", rgb(sky.sun_direction()));
  text += fmt::format("sun light direction (where it shines): {}\n", rgb(-sky.sun_direction()));
  text += fmt::format("sun irradiance facing the sun: {} W/m^2, luminance {:.4g} W/m^2 (transmittance {})\n", rgb(E),
                      luminance_of(E), rgb(sky.sun_transmittance()));
  text += fmt::format("sun as KHR_lights_punctual: directional, intensity {:.6g} lx, color ({:.6g}, {:.6g}, {:.6g})\n",
                      sun.intensity, sun.color.x, sun.color.y, sun.color.z);
  text += fmt::format("zenith luminance: {:.6g} cd/m^2 (radiance luminance {:.4g} W/(sr m^2))\n",
                      sky.zenith_luminance(), sky.zenith_luminance() / scenes::PunctualLight::kLumensPerWatt);
  text += fmt::format("sky irradiance on the ground: {} W/m^2 (luminance {:.4g})\n", rgb(sky.sky_irradiance()),
                      luminance_of(sky.sky_irradiance()));
  text += fmt::format("ground radiance (albedo {} x (sky + sun irradiance) / pi): {} W/(sr m^2)\n",
                      sky.parameters().ground_albedo, rgb(sky.ground_radiance()));
  return text;
}

void run(const SkyOptions& o) {
  const std::filesystem::path out(o.out);
  const std::string ext = out.extension().string();
  if (ext != ".exr" && ext != ".hdr") fail("--out {}: the sky is HDR, write it as .exr (or .hdr)", o.out);
  scenes::SkyParameters parameters;
  parameters.turbidity = o.turbidity;
  parameters.sun_elevation = o.sun_elevation_degrees * kDegrees;
  parameters.sun_azimuth = o.sun_azimuth_degrees * kDegrees;
  parameters.ground_albedo = o.ground_albedo;
  const scenes::PreethamSky sky(parameters);
  const Image image = scenes::sky_image(sky, o.width);
  if (out.has_parent_path()) std::filesystem::create_directories(out.parent_path());
  write_image(out, image);
  std::cout << sky_report(sky, o.out, o.width);
}

}  // namespace

void add_scenes_sky_command(CLI::App& scenes) {
  auto options = std::make_shared<SkyOptions>();
  auto* cmd = scenes.add_subcommand(
      "sky",
      "Write the Preetham clear sky as an equirectangular EXR (the toolkit's mapping, radiance in "
      "W/(sr m^2), a constant ground below the horizon, no sun disc) and print the sun as a directional "
      "light: direction and irradiance (docs/sky.md)");
  cmd->add_option("--out", options->out, "the EXR to write")->required();
  cmd->add_option("--turbidity", options->turbidity, "atmospheric turbidity T in [1.7, 10]: 2 very clear, 3 clear, 6 hazy")
      ->capture_default_str();
  cmd->add_option("--sun-elevation", options->sun_elevation_degrees, "sun elevation above the horizon, degrees, [0, 90]")
      ->capture_default_str();
  cmd->add_option("--sun-azimuth", options->sun_azimuth_degrees,
                  "sun azimuth, degrees from -Z towards +X (0: the map's centre column, 90: towards +X)")
      ->capture_default_str();
  cmd->add_option("--ground-albedo", options->ground_albedo, "albedo of the ground below the horizon, [0, 1]")
      ->capture_default_str();
  cmd->add_option("--width", options->width, "image width in pixels (height = width / 2), even, 8 to 65536")
      ->capture_default_str();
  cmd->callback([options] { run(*options); });
}

}  // namespace phyir::cli
