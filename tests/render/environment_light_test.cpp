// The equirect environment light: texel-exact pdf (normalised, matching sample()),
// chi-square tests of the samples per texel and inside texels, the constant and black
// special cases and degenerate image shapes.
#include "phyir/render/environment_light.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

#include "chi_square.h"
#include "phyir/core/safe_math.h"
#include "phyir/render/equirect.h"
#include "phyir/render/rng.h"
#include "phyir/render/sampling.h"

namespace phyir::render {
namespace {

// The three uniforms of EnvironmentLight::sample.
glm::vec3 next_3d(Rng& rng) {
  const float a = rng.next_float();
  return glm::vec3(a, rng.next_2d());
}

// A W x H RGB image with smooth variation, a dark band, a black texel and a bright "sun".
Image structured_image(int w, int h) {
  Image img(w, h, 3);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const float s = 0.2f + 0.15f * std::sin(0.7f * x) * std::cos(0.4f * y) + 0.1f * float(y) / h;
      img.at(x, y, 0) = s;
      img.at(x, y, 1) = 0.8f * s;
      img.at(x, y, 2) = (x % 3 == 0) ? 1.2f * s : 0.5f * s;
    }
  }
  if (w > 2 && h > 2) {
    for (int x = 0; x < w; ++x) img.at(x, h - 1, 0) = img.at(x, h - 1, 1) = img.at(x, h - 1, 2) = 0.0f;
    img.at(w / 3, h / 4, 0) = 50.0f;  // the sun
    img.at(w / 3, h / 4, 1) = 45.0f;
    img.at(w / 3, h / 4, 2) = 40.0f;
  }
  return img;
}

// pmf of each texel computed here, independently: luminance x solid angle, normalised.
std::vector<double> texel_pmf(const Image& img) {
  std::vector<double> p(static_cast<size_t>(img.width) * img.height);
  double total = 0.0;
  for (int y = 0; y < img.height; ++y) {
    for (int x = 0; x < img.width; ++x) {
      const glm::vec3 c(img.at(x, y, 0), img.at(x, y, img.channels > 1 ? 1 : 0), img.at(x, y, img.channels > 2 ? 2 : 0));
      p[y * img.width + x] = double(luminance(c)) * equirect_texel_solid_angle(y, img.width, img.height);
      total += p[y * img.width + x];
    }
  }
  for (double& v : p) v /= total;
  return p;
}

glm::ivec2 texel_of(const glm::vec3& d, int w, int h) {
  const glm::vec2 uv = equirect_uv(d);
  return glm::ivec2(std::min(int(uv.x * w), w - 1), std::min(int(uv.y * h), h - 1));
}

TEST(EnvironmentLight, PdfIntegratesToOne) {
  const Image img = structured_image(32, 16);
  const EnvironmentLight env(img);
  // Exact: the pdf is constant per texel.
  double exact = 0.0;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x)
      exact += double(env.pdf(equirect_direction({(x + 0.5f) / img.width, (y + 0.5f) / img.height}))) *
               equirect_texel_solid_angle(y, img.width, img.height);
  EXPECT_NEAR(exact, 1.0, 1e-5);
  // Independent quadrature on a (theta, phi) grid about +Z, which cuts across texels.
  const test::SphereGrid grid({0, 0, 1}, 1.0f, 400, 800);
  const double quadrature = grid.integrate([&](const glm::vec3& d) { return double(env.pdf(d)); }, 2);
  std::cout << "pdf integral: texel sum " << exact << ", quadrature " << quadrature << "\n";
  EXPECT_NEAR(quadrature, 1.0, 2e-3);
}

TEST(EnvironmentLight, SamplePdfAndRadianceMatchTheLookups) {
  const Image img = structured_image(32, 16);
  const EnvironmentLight env(img, 2.0f);
  const std::vector<double> pmf = texel_pmf(img);
  Rng rng(9, 9);
  int pdf_mismatch = 0, radiance_mismatch = 0, analytic_mismatch = 0;
  const int n = 200000;
  for (int i = 0; i < n; ++i) {
    glm::vec3 d, L;
    float p;
    ASSERT_TRUE(env.sample(next_3d(rng), &d, &L, &p));
    ASSERT_NEAR(glm::length(d), 1.0f, 1e-5f);
    if (!(std::abs(env.pdf(d) - p) <= 1e-5f * p)) ++pdf_mismatch;
    if (env.radiance(d) != L) ++radiance_mismatch;
    const glm::ivec2 t = texel_of(d, img.width, img.height);
    const double expected = pmf[t.y * img.width + t.x] / equirect_texel_solid_angle(t.y, img.width, img.height);
    if (std::abs(p - expected) > 1e-4 * expected) ++analytic_mismatch;
  }
  std::cout << "pdf mismatches " << pdf_mismatch << ", radiance mismatches " << radiance_mismatch
            << ", analytic mismatches " << analytic_mismatch << " of " << n << "\n";
  // A sample rounding onto a texel border may land in the neighbour: allow 1e-4 of them.
  EXPECT_LE(pdf_mismatch, n / 10000);
  EXPECT_LE(radiance_mismatch, n / 10000);
  EXPECT_LE(analytic_mismatch, n / 10000);
  // Scale multiplies the radiance, not the pdf.
  const EnvironmentLight unscaled(img);
  const glm::vec3 probe = glm::normalize(glm::vec3(0.3f, 0.4f, -0.5f));
  EXPECT_EQ(unscaled.pdf(probe), env.pdf(probe));
  EXPECT_FLOAT_EQ(2.0f * unscaled.radiance(probe).x, env.radiance(probe).x);
}

TEST(EnvironmentLight, SamplesFollowThePdfPerTexel) {
  const Image img = structured_image(32, 16);
  const EnvironmentLight env(img);
  const std::vector<double> pmf = texel_pmf(img);
  const int n = 500000;
  std::vector<double> observed(pmf.size(), 0.0), expected(pmf.size());
  Rng rng(12, 1);
  for (int i = 0; i < n; ++i) {
    glm::vec3 d, L;
    float p;
    ASSERT_TRUE(env.sample(next_3d(rng), &d, &L, &p));
    const glm::ivec2 t = texel_of(d, img.width, img.height);
    observed[t.y * img.width + t.x] += 1.0;
  }
  for (size_t i = 0; i < pmf.size(); ++i) expected[i] = pmf[i] * n;
  const test::ChiSquareResult r = test::chi_square_test(observed, expected);
  std::cout << "per-texel chi-square: " << r.message << "\n";
  EXPECT_TRUE(r.passed()) << r.message;
  // The black bottom row is never sampled.
  for (int x = 0; x < img.width; ++x) EXPECT_EQ(observed[(img.height - 1) * img.width + x], 0.0);
}

TEST(EnvironmentLight, SamplesAreUniformInsideTheirTexel) {
  // Split every texel into 4 x 4 cells of equal solid angle (equal steps in phi and in
  // cos theta): each should receive 1/16 of the texel's samples.
  const int w = 8, h = 4, k = 4;
  const Image img = structured_image(w, h);
  const EnvironmentLight env(img);
  const std::vector<double> pmf = texel_pmf(img);
  const int n = 400000;
  std::vector<double> observed(w * h * k * k, 0.0), expected(w * h * k * k);
  Rng rng(13, 2);
  for (int i = 0; i < n; ++i) {
    glm::vec3 d, L;
    float p;
    ASSERT_TRUE(env.sample(next_3d(rng), &d, &L, &p));
    const glm::vec2 uv = equirect_uv(d);
    const int col = std::min(int(uv.x * w), w - 1), row = std::min(int(uv.y * h), h - 1);
    const double fu = uv.x * w - col;
    const double cos_top = std::cos(M_PI * row / h), cos_bottom = std::cos(M_PI * (row + 1) / h);
    const double fc = (double(d.y) - cos_top) / (cos_bottom - cos_top);
    const int a = std::clamp(int(fu * k), 0, k - 1), b = std::clamp(int(fc * k), 0, k - 1);
    observed[((row * w + col) * k + b) * k + a] += 1.0;
  }
  for (int t = 0; t < w * h; ++t)
    for (int c = 0; c < k * k; ++c) expected[t * k * k + c] = pmf[t] * n / (k * k);
  const test::ChiSquareResult r = test::chi_square_test(observed, expected);
  std::cout << "within-texel chi-square: " << r.message << "\n";
  EXPECT_TRUE(r.passed()) << r.message;
}

TEST(EnvironmentLight, ConstantEnvironmentIsUniform) {
  const EnvironmentLight env(Image(64, 32, 3, 0.7f));
  Rng rng(5, 5);
  for (int i = 0; i < 2000; ++i) {
    const glm::vec3 d = sample_uniform_sphere(rng.next_2d());
    EXPECT_NEAR(env.pdf(d), 1.0f / (4.0f * kPi), 1e-5f / (4.0f * kPi));
    EXPECT_EQ(env.radiance(d), glm::vec3(0.7f));
    glm::vec3 s, L;
    float p;
    ASSERT_TRUE(env.sample(next_3d(rng), &s, &L, &p));
    EXPECT_NEAR(p, 1.0f / (4.0f * kPi), 1e-5f / (4.0f * kPi));
  }
}

TEST(EnvironmentLight, BlackEnvironmentCannotBeSampled) {
  const EnvironmentLight env(Image(16, 8, 4, 0.0f));
  glm::vec3 d, L;
  float p = -1.0f;
  EXPECT_FALSE(env.sample({0.3f, 0.7f, 0.5f}, &d, &L, &p));
  EXPECT_EQ(env.pdf({0, 1, 0}), 0.0f);
  EXPECT_EQ(env.radiance({0, 1, 0}), glm::vec3(0.0f));
  // Negative and NaN texels are not light either.
  Image bad(4, 2, 3, -1.0f);
  bad.at(1, 1, 0) = std::nanf("");
  const EnvironmentLight env2(bad);
  EXPECT_FALSE(env2.sample({0.3f, 0.7f, 0.5f}, &d, &L, &p));
}

TEST(EnvironmentLight, DegenerateShapesAndGreyImages) {
  // 1 x N (one column), N x 1 (one row), 1 x 1 and a single-channel image.
  const Image shapes[] = {structured_image(1, 8), structured_image(8, 1), structured_image(1, 1)};
  for (const Image& img : shapes) {
    const EnvironmentLight env(img);
    double sum = 0.0;
    for (int y = 0; y < img.height; ++y)
      for (int x = 0; x < img.width; ++x)
        sum += double(env.pdf(equirect_direction({(x + 0.5f) / img.width, (y + 0.5f) / img.height}))) *
               equirect_texel_solid_angle(y, img.width, img.height);
    EXPECT_NEAR(sum, 1.0, 1e-5) << img.width << "x" << img.height;
    Rng rng(6, 6);
    int mismatches = 0;
    std::vector<double> observed(size_t(img.width) * img.height, 0.0);
    const int n = 50000;
    for (int i = 0; i < n; ++i) {
      glm::vec3 d, L;
      float p;
      ASSERT_TRUE(env.sample(next_3d(rng), &d, &L, &p));
      if (!(std::abs(env.pdf(d) - p) <= 1e-5f * p)) ++mismatches;
      const glm::ivec2 t = texel_of(d, img.width, img.height);
      observed[t.y * img.width + t.x] += 1.0;
    }
    EXPECT_LE(mismatches, n / 10000) << img.width << "x" << img.height;
    if (img.width * img.height > 1) {
      std::vector<double> expected = texel_pmf(img);
      for (double& e : expected) e *= n;
      const test::ChiSquareResult r = test::chi_square_test(observed, expected);
      EXPECT_TRUE(r.passed()) << img.width << "x" << img.height << ": " << r.message;
    }
  }
  Image grey(8, 4, 1, 0.5f);
  grey.at(2, 1) = 4.0f;
  const EnvironmentLight env(grey);
  const glm::vec3 d = equirect_direction({2.5f / 8.0f, 1.5f / 4.0f});
  EXPECT_EQ(env.radiance(d), glm::vec3(4.0f));
  EXPECT_NEAR(env.pdf(d) / env.pdf(equirect_direction({6.5f / 8.0f, 1.5f / 4.0f})), 8.0f, 1e-4f);
}

TEST(EnvironmentLight, RadianceLookupFollowsTheEquirectConvention) {
  // One bright texel per direction of interest in a 4 x 2 image: column 2 of row 0 looks
  // up and towards +X (u in [0.5, 0.75)); column 0 of row 1 looks down towards -X/+Z.
  Image img(4, 2, 3, 0.0f);
  img.at(2, 0, 0) = 1.0f;
  img.at(0, 1, 1) = 1.0f;
  const EnvironmentLight env(img);
  EXPECT_EQ(env.radiance(glm::normalize(glm::vec3(0.3f, 0.5f, -0.3f))), glm::vec3(1, 0, 0));
  EXPECT_EQ(env.radiance(glm::normalize(glm::vec3(-0.3f, -0.5f, 0.3f))), glm::vec3(0, 1, 0));
  EXPECT_EQ(env.radiance(glm::normalize(glm::vec3(-0.3f, 0.5f, -0.3f))), glm::vec3(0, 0, 0));
}

}  // namespace
}  // namespace phyir::render
