#pragma once
// A clear daylight sky and its sun, for scenes lit through windows (docs/sky.md):
//   the sky: Preetham, Shirley and Smits, "A Practical Analytic Model for Daylight"
//   (SIGGRAPH 1999), appendix A.2: Perez et al.'s distribution F(theta, gamma) for the
//   luminance Y and the chromaticities x, y, scaled by the zenith values;
//   the ground below the horizon: a Lambertian plane of constant radiance
//   albedo x (sky + sun irradiance on it) / pi;
//   the sun: a directional light whose irradiance is the solar illuminance outside the
//   atmosphere times the paper's Rayleigh and aerosol transmittances (appendix A.1).
// Units are the toolkit's (docs/conventions.md#lights): luminance in cd/m^2 becomes
// radiance at 683 lm/W, so the sky map's radiance and the sun's irradiance are W/(sr m^2)
// and W/m^2 in the sense the renderer reads glTF lights and emission, consistent with each
// other. Directions are world space, +Y up; the sky is an image in the toolkit's equirect
// mapping (core/equirect.h).
#include <glm/glm.hpp>

#include <string>

#include "phyir/core/image.h"
#include "phyir/scenes/gltf_writer.h"

namespace phyir::scenes {

struct SkyParameters {
  double turbidity = 3.0;      // T in [1.7, 10]: 2 very clear, 3 clear, 6 hazy (the paper's fit covers 2-6 best)
  double sun_elevation = 0.6;  // radians above the horizon, in [0, pi/2]
  double sun_azimuth = 0.0;    // radians from -Z towards +X: the sun is in the map's column u = 0.5 + azimuth / 2 pi
  double ground_albedo = 0.2;  // the ground below the horizon, in [0, 1]

  // Throws phyir::Error naming the parameter and its range.
  void validate() const;
};

// Perez et al.'s sky distribution (Preetham eq. 3) for one quantity:
// F(theta, gamma) = (1 + A e^(B / cos theta)) (1 + C e^(D gamma) + E cos^2 gamma), theta
// the view's angle from the zenith, gamma its angle from the sun.
struct PerezDistribution {
  double A = 0.0, B = 0.0, C = 0.0, D = 0.0, E = 0.0;
  double operator()(double cos_theta, double gamma) const;
};

class PreethamSky {
 public:
  // Solar illuminance outside the atmosphere, normal to the beam (the IES value Radiance's
  // gendaylit uses).
  static constexpr double kSolarIlluminanceLux = 127500.0;

  explicit PreethamSky(const SkyParameters& parameters);  // validates them

  const SkyParameters& parameters() const { return parameters_; }
  glm::dvec3 sun_direction() const { return sun_direction_; }  // unit, towards the sun

  // The paper's zenith values: luminance in cd/m^2 (its formula gives kcd/m^2) and (x, y).
  double zenith_luminance() const { return zenith_luminance_; }
  glm::dvec2 zenith_chromaticity() const { return zenith_chromaticity_; }

  // CIE xyY of the sky towards a unit `direction` with direction.y > 0; Y in cd/m^2.
  glm::dvec3 sky_xyY(const glm::dvec3& direction) const;
  // Radiance towards a unit `direction`, linear Rec.709 in W/(sr m^2): the sky above the
  // horizon (xyY to XYZ, Y / 683, the Rec.709 matrix, negatives clamped to 0), the
  // ground below it. No sun disc: the sun is the directional light.
  glm::dvec3 radiance(const glm::dvec3& direction) const;
  glm::dvec3 ground_radiance() const { return ground_radiance_; }

  // Irradiance (W/m^2, RGB) of an upward-facing horizontal surface from the sky dome alone
  // (numerical quadrature of radiance x cos theta over the upper hemisphere).
  glm::dvec3 sky_irradiance() const { return sky_irradiance_; }
  // The sun's Rayleigh x aerosol transmittance at 650, 570 and 475 nm (R, G, B).
  glm::dvec3 sun_transmittance() const;
  // The sun's irradiance (W/m^2, RGB) on a surface facing it: kSolarIlluminanceLux / 683 x
  // sun_transmittance().
  glm::dvec3 sun_irradiance() const;

 private:
  glm::dvec3 sky_radiance(const glm::dvec3& direction) const;
  glm::dvec3 integrate_sky_irradiance() const;

  SkyParameters parameters_;
  glm::dvec3 sun_direction_;
  double sun_zenith_ = 0.0;  // theta_s, radians
  double zenith_luminance_ = 0.0;
  glm::dvec2 zenith_chromaticity_{0.0};
  PerezDistribution perez_Y_, perez_x_, perez_y_;
  glm::dvec3 sky_irradiance_{0.0};
  glm::dvec3 ground_radiance_{0.0};
};

// Preetham's Perez coefficients for luminance Y and chromaticities x, y at turbidity T.
PerezDistribution perez_luminance(double turbidity);
PerezDistribution perez_chromaticity_x(double turbidity);
PerezDistribution perez_chromaticity_y(double turbidity);

// CIE XYZ to linear Rec.709 (D65), the matrix of IEC 61966-2-1.
glm::dvec3 xyz_to_rec709(const glm::dvec3& xyz);

// The sky as a `width` x `width / 2` float RGB image in the toolkit's equirect mapping, each
// texel the radiance towards its centre. `width` must be even and in [8, 65536].
Image sky_image(const PreethamSky& sky, int width);

// The sun as a KHR_lights_punctual directional light shining along -sun_direction() with
// sun_irradiance() (lux = 683 x the brightest channel; colour = the channels relative to it).
GltfLight sun_light(const PreethamSky& sky, const std::string& name = "sun");

}  // namespace phyir::scenes
