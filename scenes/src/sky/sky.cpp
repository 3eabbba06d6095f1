// The Preetham sky (Preetham, Shirley and Smits 1999, appendix A.2) and its ground.
#include "phyir/scenes/sky.h"

#include <algorithm>
#include <cmath>

#include "phyir/core/error.h"
#include "phyir/core/safe_math.h"

namespace phyir::scenes {

namespace {

constexpr double kPiD = 3.14159265358979323846;
constexpr double kLumensPerWatt = PunctualLight::kLumensPerWatt;

// Quadrature of the sky irradiance: midpoints of a (theta, phi) grid over the upper
// hemisphere. The Perez terms vary over tenths of a radian, so 256 x 512 cells agree with
// 4x as many to better than 1e-4 relative.
constexpr int kIrradianceThetaSteps = 256;
constexpr int kIrradiancePhiSteps = 512;

// The paper's zenith chromaticity: [T^2 T 1] M [theta_s^3 theta_s^2 theta_s 1]^T.
double chromaticity_at_zenith(const double (&m)[3][4], double T, double theta_s) {
  const double t[3] = {T * T, T, 1.0};
  const double s[4] = {theta_s * theta_s * theta_s, theta_s * theta_s, theta_s, 1.0};
  double sum = 0.0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 4; ++j) sum += t[i] * m[i][j] * s[j];
  return sum;
}

constexpr double kZenithX[3][4] = {{0.00166, -0.00375, 0.00209, 0.0},
                                   {-0.02903, 0.06377, -0.03202, 0.00394},
                                   {0.11693, -0.21196, 0.06052, 0.25886}};
constexpr double kZenithY[3][4] = {{0.00275, -0.00610, 0.00317, 0.0},
                                   {-0.04214, 0.08970, -0.04153, 0.00516},
                                   {0.15346, -0.26756, 0.06670, 0.26688}};

// The paper's zenith luminance, converted from kcd/m^2 to cd/m^2.
double zenith_luminance_cd(double T, double theta_s) {
  const double chi = (4.0 / 9.0 - T / 120.0) * (kPiD - 2.0 * theta_s);
  return 1000.0 * ((4.0453 * T - 4.9710) * std::tan(chi) - 0.2155 * T + 2.4192);
}

void check_range(const char* name, double value, double lo, double hi, const char* unit) {
  if (!(value >= lo && value <= hi))
    fail("sky: {} is {:.6g}{}: must be in [{}, {}]{}", name, value, unit, lo, hi, unit);
}

}  // namespace

void SkyParameters::validate() const {
  // Below 1.7 the luminance's B coefficient turns positive and F(theta, gamma) grows without
  // bound towards the horizon; above 10 the fit is far outside the data it was made from.
  check_range("turbidity", turbidity, 1.7, 10.0, "");
  check_range("sun elevation", sun_elevation * 180.0 / kPiD, 0.0, 90.0, " degrees");
  if (!std::isfinite(sun_azimuth)) fail("sky: sun azimuth is {}: must be finite", sun_azimuth);
  check_range("ground albedo", ground_albedo, 0.0, 1.0, "");
}

double PerezDistribution::operator()(double cos_theta, double gamma) const {
  const double cos_gamma = std::cos(gamma);
  return (1.0 + A * std::exp(B / cos_theta)) * (1.0 + C * std::exp(D * gamma) + E * cos_gamma * cos_gamma);
}

PerezDistribution perez_luminance(double T) {
  return {0.1787 * T - 1.4630, -0.3554 * T + 0.4275, -0.0227 * T + 5.3251, 0.1206 * T - 2.5771, -0.0670 * T + 0.3703};
}

PerezDistribution perez_chromaticity_x(double T) {
  return {-0.0193 * T - 0.2592, -0.0665 * T + 0.0008, -0.0004 * T + 0.2125, -0.0641 * T - 0.8989, -0.0033 * T + 0.0452};
}

PerezDistribution perez_chromaticity_y(double T) {
  return {-0.0167 * T - 0.2608, -0.0950 * T + 0.0092, -0.0079 * T + 0.2102, -0.0441 * T - 1.6537, -0.0109 * T + 0.0529};
}

glm::dvec3 xyz_to_rec709(const glm::dvec3& c) {
  return {3.2406 * c.x - 1.5372 * c.y - 0.4986 * c.z, -0.9689 * c.x + 1.8758 * c.y + 0.0415 * c.z,
          0.0557 * c.x - 0.2040 * c.y + 1.0570 * c.z};
}

PreethamSky::PreethamSky(const SkyParameters& parameters) : parameters_(parameters) {
  parameters_.validate();
  const double e = parameters_.sun_elevation, a = parameters_.sun_azimuth;
  sun_direction_ = {std::cos(e) * std::sin(a), std::sin(e), -std::cos(e) * std::cos(a)};
  sun_zenith_ = 0.5 * kPiD - e;
  const double T = parameters_.turbidity;
  zenith_luminance_ = zenith_luminance_cd(T, sun_zenith_);
  zenith_chromaticity_ = {chromaticity_at_zenith(kZenithX, T, sun_zenith_),
                          chromaticity_at_zenith(kZenithY, T, sun_zenith_)};
  perez_Y_ = perez_luminance(T);
  perez_x_ = perez_chromaticity_x(T);
  perez_y_ = perez_chromaticity_y(T);
  sky_irradiance_ = integrate_sky_irradiance();
  const glm::dvec3 ground_irradiance = sky_irradiance_ + sun_irradiance() * std::sin(e);
  ground_radiance_ = parameters_.ground_albedo * ground_irradiance / kPiD;
}

glm::dvec3 PreethamSky::sky_xyY(const glm::dvec3& d) const {
  const double cos_theta = d.y;
  const double gamma = std::acos(std::clamp(glm::dot(d, sun_direction_), -1.0, 1.0));
  // Each quantity is its zenith value times F(theta, gamma) / F(zenith, sun).
  const auto relative = [&](const PerezDistribution& f) { return f(cos_theta, gamma) / f(1.0, sun_zenith_); };
  return {zenith_chromaticity_.x * relative(perez_x_), zenith_chromaticity_.y * relative(perez_y_),
          zenith_luminance_ * relative(perez_Y_)};
}

glm::dvec3 PreethamSky::sky_radiance(const glm::dvec3& d) const {
  const glm::dvec3 xyY = sky_xyY(d);
  const double Y = xyY.z / kLumensPerWatt;
  const glm::dvec3 xyz(xyY.x / xyY.y * Y, Y, (1.0 - xyY.x - xyY.y) / xyY.y * Y);
  // A chromaticity outside the Rec.709 gamut (none in the paper's range, in practice) loses
  // its negative channel.
  return glm::max(xyz_to_rec709(xyz), glm::dvec3(0.0));
}

glm::dvec3 PreethamSky::radiance(const glm::dvec3& d) const {
  return d.y > 0.0 ? sky_radiance(d) : ground_radiance_;
}

glm::dvec3 PreethamSky::integrate_sky_irradiance() const {
  const double d_theta = 0.5 * kPiD / kIrradianceThetaSteps, d_phi = 2.0 * kPiD / kIrradiancePhiSteps;
  glm::dvec3 sum(0.0);
  for (int i = 0; i < kIrradianceThetaSteps; ++i) {
    const double theta = (i + 0.5) * d_theta;
    const double weight = std::cos(theta) * std::sin(theta) * d_theta * d_phi;
    for (int j = 0; j < kIrradiancePhiSteps; ++j) {
      const double phi = (j + 0.5) * d_phi;
      const glm::dvec3 d(std::sin(theta) * std::sin(phi), std::cos(theta), -std::sin(theta) * std::cos(phi));
      sum += sky_radiance(d) * weight;
    }
  }
  return sum;
}

}  // namespace phyir::scenes
