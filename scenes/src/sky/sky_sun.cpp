// The sun of the Preetham sky: extraterrestrial illuminance through the paper's Rayleigh and
// aerosol transmittances (appendix A.1), as a KHR_lights_punctual directional light.
#include <cmath>

#include "phyir/scenes/sky.h"

namespace phyir::scenes {

namespace {

constexpr double kPiD = 3.14159265358979323846;

// R, G, B wavelengths in micrometres: those of the RGB sun in the paper's published source.
constexpr double kWavelengths[3] = {0.650, 0.570, 0.475};

// Kasten's relative optical air mass, as the paper uses it (36.5 at the horizon).
double relative_air_mass(double sun_zenith) {
  const double zenith_degrees = sun_zenith * 180.0 / kPiD;
  return 1.0 / (std::cos(sun_zenith) + 0.15 * std::pow(93.885 - zenith_degrees, -1.253));
}

}  // namespace

// Rayleigh scattering exp(-0.008735 lambda^-4.08 m) and Angstrom's aerosol extinction
// exp(-beta lambda^-alpha m), alpha = 1.3, beta from the turbidity (paper appendix A.1).
// Ozone, mixed gases and water vapour (a few percent in the visible) are left out.
glm::dvec3 PreethamSky::sun_transmittance() const {
  const double m = relative_air_mass(0.5 * kPiD - parameters_.sun_elevation);
  const double beta = 0.04608365822050 * parameters_.turbidity - 0.04586025928522;
  constexpr double kAlpha = 1.3;
  glm::dvec3 t;
  for (int c = 0; c < 3; ++c) {
    const double rayleigh = std::exp(-0.008735 * std::pow(kWavelengths[c], -4.08) * m);
    const double aerosol = std::exp(-beta * std::pow(kWavelengths[c], -kAlpha) * m);
    t[c] = rayleigh * aerosol;
  }
  return t;
}

glm::dvec3 PreethamSky::sun_irradiance() const {
  return sun_transmittance() * (kSolarIlluminanceLux / PunctualLight::kLumensPerWatt);
}

GltfLight sun_light(const PreethamSky& sky, const std::string& name) {
  GltfLight light;
  light.name = name;
  light.type = PunctualLight::Type::Directional;
  light.set_radiometric(glm::vec3(sky.sun_irradiance()));
  light.direction = glm::vec3(-sky.sun_direction());
  return light;
}

}  // namespace phyir::scenes
