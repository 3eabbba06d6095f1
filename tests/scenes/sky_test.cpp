// The Preetham sky and its sun, checked against the paper's formulas typed in again here
// (appendix A.2: Perez coefficients, zenith luminance and chromaticity; A.1: the sun's
// Rayleigh and aerosol transmittance), not against the model's own helpers.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

#include "phyir/core/equirect.h"
#include "phyir/core/error.h"
#include "phyir/core/safe_math.h"
#include "phyir/scenes/sky.h"

namespace phyir::scenes {
namespace {

using ::testing::HasSubstr;

constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = kPi / 180.0;

// ---- The paper, again -----------------------------------------------------------------

struct Perez5 {
  double a, b, c, d, e;
};

// Table of appendix A.2: each coefficient = slope * T + intercept.
Perez5 paper_perez(char quantity, double T) {
  switch (quantity) {
    case 'Y':
      return {0.1787 * T - 1.4630, -0.3554 * T + 0.4275, -0.0227 * T + 5.3251, 0.1206 * T - 2.5771,
              -0.0670 * T + 0.3703};
    case 'x':
      return {-0.0193 * T - 0.2592, -0.0665 * T + 0.0008, -0.0004 * T + 0.2125, -0.0641 * T - 0.8989,
              -0.0033 * T + 0.0452};
    default:
      return {-0.0167 * T - 0.2608, -0.0950 * T + 0.0092, -0.0079 * T + 0.2102, -0.0441 * T - 1.6537,
              -0.0109 * T + 0.0529};
  }
}

double paper_F(const Perez5& p, double theta, double gamma) {
  return (1 + p.a * std::exp(p.b / std::cos(theta))) * (1 + p.c * std::exp(p.d * gamma) + p.e * std::pow(std::cos(gamma), 2));
}

double paper_zenith_Y_kcd(double T, double theta_s) {
  const double chi = (4.0 / 9.0 - T / 120.0) * (kPi - 2 * theta_s);
  return (4.0453 * T - 4.9710) * std::tan(chi) - 0.2155 * T + 2.4192;
}

double paper_zenith_x(double T, double t) {
  return T * T * (0.00166 * t * t * t - 0.00375 * t * t + 0.00209 * t) +
         T * (-0.02903 * t * t * t + 0.06377 * t * t - 0.03202 * t + 0.00394) +
         (0.11693 * t * t * t - 0.21196 * t * t + 0.06052 * t + 0.25886);
}

double paper_zenith_y(double T, double t) {
  return T * T * (0.00275 * t * t * t - 0.00610 * t * t + 0.00317 * t) +
         T * (-0.04214 * t * t * t + 0.08970 * t * t - 0.04153 * t + 0.00516) +
         (0.15346 * t * t * t - 0.26756 * t * t + 0.06670 * t + 0.26688);
}

// A direction from its zenith angle and its azimuth (from -Z towards +X, as the sky's).
glm::dvec3 direction(double theta, double azimuth) {
  return {std::sin(theta) * std::sin(azimuth), std::cos(theta), -std::sin(theta) * std::cos(azimuth)};
}

// The paper's xyY for a view at (theta, azimuth) under a sun at (elevation, sun_azimuth).
glm::dvec3 paper_xyY(double T, double elevation, double sun_azimuth, double theta, double azimuth) {
  const double theta_s = kPi / 2 - elevation;
  const double gamma =
      std::acos(std::clamp(glm::dot(direction(theta, azimuth), direction(theta_s, sun_azimuth)), -1.0, 1.0));
  const auto ratio = [&](char q) { return paper_F(paper_perez(q, T), theta, gamma) / paper_F(paper_perez(q, T), 0, theta_s); };
  return {paper_zenith_x(T, theta_s) * ratio('x'), paper_zenith_y(T, theta_s) * ratio('y'),
          1000 * paper_zenith_Y_kcd(T, theta_s) * ratio('Y')};
}

double rec709_luminance(const glm::dvec3& rgb) { return 0.2126 * rgb.x + 0.7152 * rgb.y + 0.0722 * rgb.z; }

SkyParameters parameters(double T, double elevation_degrees, double azimuth_degrees, double albedo = 0.2) {
  SkyParameters p;
  p.turbidity = T;
  p.sun_elevation = elevation_degrees * kDeg;
  p.sun_azimuth = azimuth_degrees * kDeg;
  p.ground_albedo = albedo;
  return p;
}

// ---- Tests --------------------------------------------------------------------------------

TEST(PreethamSky, FiniteAndNonNegativeEverywhere) {
  for (double T : {1.7, 2.0, 3.0, 6.0, 10.0})
    for (double elevation : {0.0, 0.5, 5.0, 30.0, 60.0, 90.0}) {
      SCOPED_TRACE(testing::Message() << "T " << T << ", elevation " << elevation);
      const PreethamSky sky(parameters(T, elevation, 20.0));
      const Image image = sky_image(sky, 64);
      for (float v : image.pixels) ASSERT_TRUE(std::isfinite(v) && v >= 0.0f) << v;
      EXPECT_GT(sky.zenith_luminance(), 0.0);
      const glm::dvec3 E = sky.sun_irradiance();
      EXPECT_TRUE(std::isfinite(E.x) && E.x >= 0.0 && E.z >= 0.0);
    }
}

TEST(PreethamSky, ZenithLuminanceIsThePaperFormula) {
  for (double T : {2.0, 3.0, 6.0})
    for (double elevation : {10.0, 35.0, 70.0}) {
      const PreethamSky sky(parameters(T, elevation, 0.0));
      const double theta_s = (90.0 - elevation) * kDeg;
      const double want = 1000.0 * paper_zenith_Y_kcd(T, theta_s);
      EXPECT_NEAR(sky.zenith_luminance(), want, 1e-9 * want);
      const glm::dvec3 zenith = sky.sky_xyY({0.0, 1.0, 0.0});
      EXPECT_NEAR(zenith.z, want, 1e-9 * want);  // F(zenith) / F(zenith) = 1
      EXPECT_NEAR(zenith.x, paper_zenith_x(T, theta_s), 1e-12);
      EXPECT_NEAR(zenith.y, paper_zenith_y(T, theta_s), 1e-12);
    }
  // Clear sky, sun 35 degrees up: the formula gives 5.8 kcd/m^2.
  EXPECT_NEAR(PreethamSky(parameters(3.0, 35.0, 0.0)).zenith_luminance(), 5800.0, 10.0);
}

TEST(PreethamSky, MatchesThePerezFormulaInEveryDirection) {
  const double T = 3.0, elevation = 30.0 * kDeg, sun_azimuth = 40.0 * kDeg;
  const PreethamSky sky(parameters(T, 30.0, 40.0));
  for (double theta : {0.1, 0.5, 1.0, 1.4, 1.56})
    for (double azimuth : {-2.5, 0.0, 0.7, 2.0, 3.1}) {
      SCOPED_TRACE(testing::Message() << "theta " << theta << ", azimuth " << azimuth);
      const glm::dvec3 want = paper_xyY(T, elevation, sun_azimuth, theta, azimuth);
      const glm::dvec3 got = sky.sky_xyY(direction(theta, azimuth));
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c], want[c], 1e-9 * std::abs(want[c]));
      // The RGB radiance carries the luminance at 683 lm/W (up to the matrices' 4 digits).
      EXPECT_NEAR(rec709_luminance(sky.radiance(direction(theta, azimuth))), want.z / 683.0, 2e-3 * want.z / 683.0);
    }
}

TEST(PreethamSky, BrightestNearTheSunAndBrighteningTowardsTheHorizon) {
  const double T = 3.0, elevation = 30.0 * kDeg, sun_azimuth = 40.0 * kDeg;
  const PreethamSky sky(parameters(T, 30.0, 40.0));
  const auto Y = [&](double theta, double azimuth) { return sky.sky_xyY(direction(theta, azimuth)).z; };
  const double theta_s = kPi / 2 - elevation;
  // Around the sun (the circumsolar term C e^(D gamma)) the sky is several times its zenith.
  EXPECT_GT(Y(theta_s, sun_azimuth + 0.05), 3.0 * sky.zenith_luminance());
  // The brightest texel of the upper hemisphere is within 5 degrees of the sun.
  const Image image = sky_image(sky, 360);
  float best = 0.0f;
  glm::vec3 best_direction(0.0f);
  for (int j = 0; j < image.height / 2; ++j)
    for (int i = 0; i < image.width; ++i)
      if (image.at(i, j, 1) > best) {
        best = image.at(i, j, 1);
        best_direction = equirect_direction({(i + 0.5f) / image.width, (j + 0.5f) / image.height});
      }
  EXPECT_GT(glm::dot(glm::dvec3(best_direction), sky.sun_direction()), std::cos(5.0 * kDeg));
  // Away from the sun the gradation term (1 + A e^(B / cos theta)) brightens towards the
  // horizon: opposite the sun, and at right angles to it.
  for (double azimuth : {sun_azimuth + kPi, sun_azimuth + kPi / 2}) {
    EXPECT_GT(Y(88.0 * kDeg, azimuth), Y(60.0 * kDeg, azimuth));
    EXPECT_GT(Y(60.0 * kDeg, azimuth), Y(20.0 * kDeg, azimuth));
    EXPECT_NEAR(Y(88.0 * kDeg, azimuth), paper_xyY(T, elevation, sun_azimuth, 88.0 * kDeg, azimuth).z,
                1e-9 * Y(88.0 * kDeg, azimuth));
  }
}

TEST(PreethamSky, SymmetricAboutTheSunsVerticalPlane) {
  const PreethamSky sky(parameters(4.0, 25.0, 63.0));
  const glm::dvec3 sun = sky.sun_direction();
  const glm::dvec3 normal = glm::normalize(glm::cross(glm::dvec3(0, 1, 0), sun));  // of the vertical plane
  for (double theta : {0.2, 0.9, 1.3, 1.55})
    for (double azimuth : {0.1, 1.0, 2.2, -1.7}) {
      const glm::dvec3 d = direction(theta, azimuth);
      const glm::dvec3 mirrored = d - 2.0 * glm::dot(d, normal) * normal;
      const glm::dvec3 a = sky.radiance(d), b = sky.radiance(mirrored);
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(a[c], b[c], 1e-9 * a[c]) << theta << ", " << azimuth;
    }
  // In the image: a sun in the centre column (azimuth 0) mirrors column i onto W - 1 - i.
  const Image image = sky_image(PreethamSky(parameters(4.0, 25.0, 0.0)), 128);
  for (int j = 0; j < image.height; ++j)
    for (int i = 0; i < image.width / 2; ++i)
      for (int c = 0; c < 3; ++c)
        ASSERT_NEAR(image.at(i, j, c), image.at(image.width - 1 - i, j, c), 1e-5f * image.at(i, j, c)) << i << ", " << j;
}

TEST(PreethamSky, ImageTexelsHoldTheRadianceAtTheirCentresInTheToolkitsMapping) {
  const PreethamSky sky(parameters(3.0, 40.0, 90.0));
  const Image image = sky_image(sky, 256);
  ASSERT_EQ(image.width, 256);
  ASSERT_EQ(image.height, 128);
  ASSERT_EQ(image.channels, 3);
  for (int j : {0, 20, 63, 64, 100, 127})
    for (int i : {0, 77, 128, 191, 255}) {
      const glm::vec3 d = equirect_direction({(i + 0.5f) / 256.0f, (j + 0.5f) / 128.0f});
      const glm::dvec3 want = sky.radiance(glm::normalize(glm::dvec3(d)));
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(image.at(i, j, c), want[c], 1e-5 * want[c] + 1e-7);
    }
  // Azimuth 90 degrees puts the sun towards +X: column u = 0.75.
  const glm::vec2 uv = equirect_uv(glm::vec3(sky.sun_direction()));
  EXPECT_NEAR(uv.x, 0.75f, 1e-6f);
  EXPECT_NEAR(uv.y, 50.0f / 180.0f, 1e-6f);
}

TEST(PreethamSky, GroundRadianceIsAlbedoTimesSkyAndSunIrradianceOverPi) {
  const SkyParameters p = parameters(3.0, 35.0, 10.0, 0.3);
  const PreethamSky sky(p);
  // The sky's irradiance on the ground again, from the image's texels (their exact solid
  // angles), independent of the model's quadrature.
  const Image image = sky_image(sky, 1024);
  glm::dvec3 E_sky(0.0);
  for (int j = 0; j < image.height / 2; ++j) {
    const double cos_theta = std::cos(kPi * (j + 0.5) / image.height);
    const double solid_angle = equirect_texel_solid_angle(j, image.width, image.height);
    for (int i = 0; i < image.width; ++i)
      for (int c = 0; c < 3; ++c) E_sky[c] += image.at(i, j, c) * cos_theta * solid_angle;
  }
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(sky.sky_irradiance()[c], E_sky[c], 5e-3 * E_sky[c]);
  const glm::dvec3 want = 0.3 * (sky.sky_irradiance() + sky.sun_irradiance() * std::sin(35.0 * kDeg)) / kPi;
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(sky.ground_radiance()[c], want[c], 1e-12 * want[c]);
  // Every texel below the horizon is the ground.
  for (int j = image.height / 2; j < image.height; ++j)
    for (int i = 0; i < image.width; i += 37)
      for (int c = 0; c < 3; ++c) ASSERT_FLOAT_EQ(image.at(i, j, c), float(want[c]));
}

TEST(PreethamSky, SunIsTheSolarIlluminanceThroughRayleighAndAerosolTransmittance) {
  const double T = 3.0, elevation = 35.0;
  const PreethamSky sky(parameters(T, elevation, 10.0));
  const double theta_s = (90.0 - elevation) * kDeg;
  const double m = 1.0 / (std::cos(theta_s) + 0.15 * std::pow(93.885 - 90.0 + elevation, -1.253));
  const double beta = 0.04608365822050 * T - 0.04586025928522;
  const double lambda[3] = {0.65, 0.57, 0.475};
  glm::dvec3 E;
  for (int c = 0; c < 3; ++c)
    E[c] = 127500.0 / 683.0 * std::exp(-0.008735 * std::pow(lambda[c], -4.08) * m) *
           std::exp(-beta * std::pow(lambda[c], -1.3) * m);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(sky.sun_irradiance()[c], E[c], 1e-9 * E[c]);
  // A clear sky's direct sun: about 79 klx at 35 degrees; warmer than white.
  EXPECT_NEAR(683.0 * rec709_luminance(E), 79300.0, 500.0);
  EXPECT_GT(E.x, E.z);
  // The light: shining down along -sun_direction, its W/m^2 back from lux at 683 lm/W.
  const GltfLight sun = sun_light(sky);
  EXPECT_EQ(sun.type, PunctualLight::Type::Directional);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(sun.direction[c], -sky.sun_direction()[c], 1e-7);
  PunctualLight loaded;
  loaded.color = sun.color;
  loaded.intensity = sun.intensity;
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(loaded.radiometric()[c], E[c], 1e-6 * E[c]);
  // Lower sun, hazier air: less light.
  EXPECT_LT(luminance(glm::vec3(PreethamSky(parameters(T, 5.0, 0.0)).sun_irradiance())), luminance(glm::vec3(E)));
  EXPECT_LT(luminance(glm::vec3(PreethamSky(parameters(8.0, elevation, 0.0)).sun_irradiance())),
            luminance(glm::vec3(E)));
}

TEST(PreethamSky, ParametersOutOfRangeAreRefusedNamingThem) {
  const auto error = [](const SkyParameters& p) {
    try {
      PreethamSky sky(p);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("(no error)");
  };
  EXPECT_THAT(error(parameters(1.5, 30, 0)), HasSubstr("turbidity is 1.5: must be in [1.7, 10]"));
  EXPECT_THAT(error(parameters(3, -2, 0)), HasSubstr("sun elevation is -2 degrees: must be in [0, 90] degrees"));
  EXPECT_THAT(error(parameters(3, 91, 0)), HasSubstr("sun elevation is 91 degrees"));
  EXPECT_THAT(error(parameters(3, 30, 0, 1.5)), HasSubstr("ground albedo is 1.5"));
  EXPECT_THAT(error(parameters(3, 30, NAN)), HasSubstr("sun azimuth is nan"));
  const PreethamSky sky(parameters(3, 30, 0));
  EXPECT_THROW(sky_image(sky, 63), Error);
  EXPECT_THROW(sky_image(sky, 4), Error);
}

}  // namespace
}  // namespace phyir::scenes
