// The rendering layer: its BRDF against render/'s, Monte-Carlo integrals against quadrature,
// the mirror branch, the equirect mapping, and finite outputs and gradients in extreme cases.
#include <unistd.h>

#include <cstdlib>
#include <glm/glm.hpp>
#include <random>

#include "phyir/core/safe_math.h"
#include "phyir/render/brdf.h"
#include "phyir/render/equirect.h"
#include "phyir/model/training.h"
#include "render_layer.h"

namespace pm_check = phyir::model;

namespace pm = phyir::model;
namespace pr = phyir::render;

namespace {

constexpr double kPi = 3.14159265358979323846;

bool close_rel(double a, double b, double rel, double abs_tol = 1e-12) {
  return std::abs(a - b) <= rel * std::max(std::abs(a), std::abs(b)) + abs_tol;
}

struct ThreadSetup {
  ThreadSetup() { torch::set_num_threads(1); }  // shared machines: no OpenMP spinning
} thread_setup;

// A smooth, asymmetric environment: tests orientation (up, +X) as well as magnitudes.
double env(const glm::dvec3& d) { return 1.0 + 0.5 * d.y + 0.3 * d.x; }

// Per-pixel probes [1,H,W,h,w,3] tabulating env() at the texel centres.
torch::Tensor env_probes(int H, int W, int h, int w) {
  const torch::Tensor dirs = pm::pixel_directions(h, w, torch::TensorOptions().dtype(torch::kDouble));
  const torch::Tensor val = 1.0 + 0.5 * dirs.select(-1, 1) + 0.3 * dirs.select(-1, 0);
  return val.view({1, 1, 1, h, w, 1}).expand({1, H, W, h, w, 3}).to(torch::kFloat).contiguous();
}

// Orthonormal basis around n (any: the integrals are isotropic).
void basis(const glm::dvec3& n, glm::dvec3* t, glm::dvec3* b) {
  const glm::dvec3 a = std::abs(n.x) > 0.9 ? glm::dvec3(0, 1, 0) : glm::dvec3(1, 0, 0);
  *t = glm::normalize(glm::cross(a, n));
  *b = glm::cross(n, *t);
}

// Quadrature of f_r cos L over the hemisphere with render::brdf_eval (midpoint rule, fine
// grid in cos theta so grazing angles cost nothing).
glm::dvec3 reference_integral(const pr::BrdfParams& p, const glm::dvec3& n, const glm::dvec3& v,
                              bool constant_light) {
  glm::dvec3 t, b;
  basis(n, &t, &b);
  const glm::vec3 wo(glm::dot(v, t), glm::dot(v, b), glm::dot(v, n));
  const int NT = 800, NP = 800;  // fine enough for an alpha = 0.09 lobe at grazing view (~0.1%)
  glm::dvec3 sum(0.0);
  for (int i = 0; i < NT; ++i) {
    const double mu = (i + 0.5) / NT;  // cos theta; d omega = d mu d phi
    const double s = std::sqrt(1.0 - mu * mu);
    for (int j = 0; j < NP; ++j) {
      const double phi = 2.0 * kPi * (j + 0.5) / NP;
      const glm::dvec3 l(s * std::cos(phi), s * std::sin(phi), mu);
      const glm::dvec3 f = glm::dvec3(pr::brdf_eval(p, wo, glm::vec3(l)));
      const glm::dvec3 lw = l.x * t + l.y * b + l.z * n;
      sum += f * mu * (constant_light ? 1.0 : env(lw));
    }
  }
  return sum * (2.0 * kPi / NP) / static_cast<double>(NT);
}

// Pixel directions of an H x W panorama (the layer's view rays are their negatives).
glm::dvec3 pixel_dir(int row, int col, int H, int W) {
  return glm::dvec3(pr::equirect_direction({(col + 0.5f) / W, (row + 0.5f) / H}));
}

}  // namespace

TEST(ModelBrdf, TermsMatchRenderer) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> U(0.0f, 1.0f);
  const int N = 4000;
  std::vector<float> noh(N), alpha(N), voh(N), f0(N), nox(N), k(N), r(N), nol(N), m(N), bc(N);
  for (int i = 0; i < N; ++i) {
    noh[i] = i % 10 == 0 ? 1.0f : (i % 10 == 1 ? 0.0f : U(rng));
    alpha[i] = i % 7 == 0 ? 0.0f : U(rng) * U(rng);
    voh[i] = U(rng);
    f0[i] = U(rng);
    nox[i] = U(rng);
    k[i] = 0.125f + U(rng) * 0.375f;
    r[i] = i % 5 == 0 ? 0.0f : U(rng);
    nol[i] = U(rng);
    m[i] = U(rng);
    bc[i] = U(rng);
  }
  auto T = [](const std::vector<float>& v) { return torch::tensor(v); };
  const auto D = pm::D_GGX(T(noh), T(alpha));
  const auto F = pm::F_SchlickSG(T(f0), T(voh));
  const auto G1 = pm::G1_SmithSchlick(T(nox), T(k));
  const auto G = pm::G_SmithSchlick(T(nox), T(nol), T(r));
  const auto F0 = pm::specular_F0(T(bc), T(m));
  const auto Fd = pm::Fd_Lambert(T(bc), T(m));
  double worst = 0.0;
  for (int i = 0; i < N; ++i) {
    const double ref[6] = {pr::D_GGX(noh[i], alpha[i]),
                           pr::F_SchlickSG(glm::vec3(f0[i]), voh[i]).x,
                           pr::G1_SmithSchlick(nox[i], k[i]),
                           pr::G_SmithSchlick(nox[i], nol[i], r[i]),
                           pr::specular_F0(glm::vec3(bc[i]), m[i]).x,
                           pr::Fd_Lambert(glm::vec3(bc[i]), m[i]).x};
    const double got[6] = {D[i].item<float>(), F[i].item<float>(), G1[i].item<float>(),
                           G[i].item<float>(), F0[i].item<float>(), Fd[i].item<float>()};
    for (int j = 0; j < 6; ++j) {
      const double rel = std::abs(got[j] - ref[j]) / std::max(std::abs(ref[j]), 1e-30);
      worst = std::max(worst, std::abs(got[j] - ref[j]) <= 1e-12 ? 0.0 : rel);
      ASSERT_TRUE(close_rel(got[j], ref[j], 1e-5)) << "term " << j << " case " << i << ": " << got[j] << " vs " << ref[j];
    }
  }
  std::printf("[ModelBrdf] terms: worst relative difference to render/ %.3g over %d cases\n", worst, N);
  EXPECT_EQ(static_cast<float>(pm::kMirrorRoughness), pr::kMirrorRoughness);
  EXPECT_EQ(static_cast<float>(pm::kMinCosine), phyir::kMinCosine);
}

TEST(ModelBrdf, EvalMatchesRenderer) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> U(0.0f, 1.0f);
  const float roughs[] = {0.0f, 0.005f, 0.008f, 0.01f, 0.05f, 0.3f, 0.7f, 1.0f};
  const int N = 4000;
  std::vector<float> B, R, M, wo, wi;
  auto random_dir = [&](float zmin) {
    const float z = zmin + (1.0f - zmin) * U(rng), phi = 6.2831853f * U(rng);
    const float s = std::sqrt(std::max(0.0f, 1.0f - z * z));
    return glm::vec3(s * std::cos(phi), s * std::sin(phi), z);
  };
  std::vector<glm::vec3> wos, wis;
  for (int i = 0; i < N; ++i) {
    const glm::vec3 b(U(rng), U(rng), U(rng));
    B.insert(B.end(), {b.x, b.y, b.z});
    R.push_back(roughs[i % 8]);
    M.push_back(i % 3 == 0 ? 0.0f : (i % 3 == 1 ? 1.0f : U(rng)));
    const glm::vec3 o = random_dir(i % 13 == 0 ? -0.2f : 0.0f), l = random_dir(i % 11 == 0 ? -0.2f : 0.0f);
    wos.push_back(o);
    wis.push_back(l);
    wo.insert(wo.end(), {o.x, o.y, o.z});
    wi.insert(wi.end(), {l.x, l.y, l.z});
  }
  const auto f = pm::brdf_eval(torch::tensor(B).view({N, 3}), torch::tensor(R).view({N, 1}),
                               torch::tensor(M).view({N, 1}), torch::tensor(wo).view({N, 3}),
                               torch::tensor(wi).view({N, 3}));
  const auto acc = f.accessor<float, 2>();
  double worst = 0.0;
  for (int i = 0; i < N; ++i) {
    pr::BrdfParams p;
    p.base_color = glm::vec3(B[3 * i], B[3 * i + 1], B[3 * i + 2]);
    p.roughness = R[i];
    p.metalness = M[i];
    const glm::vec3 ref = pr::brdf_eval(p, wos[i], wis[i]);
    for (int c = 0; c < 3; ++c) {
      if (ref[c] != 0.0f) worst = std::max<double>(worst, std::abs(acc[i][c] - ref[c]) / std::abs(ref[c]));
      ASSERT_TRUE(close_rel(acc[i][c], ref[c], 1e-5)) << "case " << i << " c " << c << ": " << acc[i][c]
                                                      << " vs " << ref[c] << " R " << R[i];
    }
  }
  std::printf("[ModelBrdf] brdf_eval: worst relative difference to render::brdf_eval %.3g over %d pairs\n", worst, N);
}

TEST(ModelEquirect, MatchesRendererMapping) {
  const int H = 8, W = 16;
  const auto dirs = pm::pixel_directions(H, W, torch::TensorOptions().dtype(torch::kFloat));
  const auto uv = pm::equirect_uv(dirs);
  for (int r = 0; r < H; ++r)
    for (int c = 0; c < W; ++c) {
      const glm::vec3 ref = pr::equirect_direction({(c + 0.5f) / W, (r + 0.5f) / H});
      for (int k = 0; k < 3; ++k) EXPECT_NEAR(dirs[r][c][k].item<float>(), ref[k], 1e-6);
      const glm::vec2 ruv = pr::equirect_uv(ref);
      EXPECT_NEAR(uv[r][c][0].item<float>(), ruv.x, 1e-6);
      EXPECT_NEAR(uv[r][c][1].item<float>(), ruv.y, 1e-6);
    }
  // Row 0 looks up, the centre column looks along -Z.
  EXPECT_GT(dirs[0][W / 2][1].item<float>(), 0.9f);
  EXPECT_LT(dirs[H / 2][W / 2][2].item<float>(), -0.9f);
}

// Constant probes (L = 1): the layer estimates the directional albedo; compare with the
// quadrature of render::brdf_eval. The diffuse lobe is exact: B (1 - M). The tolerance is
// 6 standard errors of the Monte-Carlo mean (estimated from 8 independent runs) + 0.3%.
TEST(ModelRenderLayer, FurnaceMatchesQuadratureOfRendererBrdf) {
  const int H = 2, W = 4, K = 8;
  torch::manual_seed(3);
  double worst = 0.0, worst_se = 0.0;
  for (float R : {0.3f, 0.6f, 1.0f})
    for (float M : {0.0f, 1.0f})
      for (float tilt : {0.0f, 1.2f}) {
        // n: the view direction -d tilted sideways by `tilt` radians.
        torch::Tensor normal = torch::zeros({1, 3, H, W});
        std::vector<glm::dvec3> ns;
        for (int r = 0; r < H; ++r)
          for (int c = 0; c < W; ++c) {
            const glm::dvec3 v = -pixel_dir(r, c, H, W);
            glm::dvec3 t, b;
            basis(v, &t, &b);
            const glm::dvec3 n = glm::normalize(std::cos(double(tilt)) * v + std::sin(double(tilt)) * t);
            ns.push_back(n);
            for (int k = 0; k < 3; ++k) normal[0][k][r][c] = n[k];
          }
        const glm::vec3 bc(0.9f, 0.6f, 0.3f);
        torch::Tensor base = torch::tensor({bc.x, bc.y, bc.z}).view({1, 3, 1, 1}).expand({1, 3, H, W});
        std::vector<torch::Tensor> runs;
        for (int k = 0; k < K; ++k) {
          const auto out = pm::render_layer(normal, base, torch::full({1, 1, H, W}, R), torch::full({1, 1, H, W}, M),
                                            torch::ones({1, H, W, 4, 8, 3}), {64, 4096, 4096});
          EXPECT_LT((out.diffuse[0][0] - bc.x * (1.0f - M)).abs().max().item<float>(), 1e-5);
          runs.push_back(out.image);
        }
        const auto all = torch::stack(runs, 0).to(torch::kDouble);
        const auto mean = all.mean(0), se = all.std(0) / std::sqrt(double(K));
        for (int r = 0; r < H; ++r)
          for (int c = 0; c < W; ++c) {
            pr::BrdfParams p{bc, R, M};
            const glm::dvec3 ref = reference_integral(p, ns[r * W + c], -pixel_dir(r, c, H, W), true);
            for (int k = 0; k < 3; ++k) {
              const double got = mean[0][k][r][c].item<double>(), s = se[0][k][r][c].item<double>();
              worst = std::max(worst, std::abs(got - ref[k]) / ref[k]);
              worst_se = std::max(worst_se, std::abs(got - ref[k]) / std::max(s, 1e-12));
              EXPECT_NEAR(got, ref[k], 6.0 * s + 0.003 * ref[k]) << "R " << R << " M " << M << " tilt " << tilt;
            }
          }
      }
  std::printf("[ModelRenderLayer] furnace (32768 specular samples): worst relative difference to quadrature %.4f, "
              "worst %.1f standard errors\n", worst, worst_se);
}

// A varying environment: checks that sampled directions land where the equirect mapping says.
TEST(ModelRenderLayer, EnvironmentIntegralMatchesQuadrature) {
  const int H = 2, W = 4;
  torch::manual_seed(5);
  torch::Tensor normal = torch::zeros({1, 3, H, W});
  std::vector<glm::dvec3> ns;
  for (int r = 0; r < H; ++r)
    for (int c = 0; c < W; ++c) {
      const glm::dvec3 v = -pixel_dir(r, c, H, W);
      glm::dvec3 t, b;
      basis(v, &t, &b);
      const glm::dvec3 n = glm::normalize(v + 0.5 * t + 0.3 * b);
      ns.push_back(n);
      for (int k = 0; k < 3; ++k) normal[0][k][r][c] = n[k];
    }
  const glm::vec3 bc(0.8f, 0.5f, 0.2f);
  torch::Tensor base = torch::tensor({bc.x, bc.y, bc.z}).view({1, 3, 1, 1}).expand({1, 3, H, W});
  double worst = 0.0;
  for (float R : {0.35f, 0.8f}) {
    for (float M : {0.0f, 1.0f}) {
      const auto out = pm::render_layer(normal, base, torch::full({1, 1, H, W}, R), torch::full({1, 1, H, W}, M),
                                        env_probes(H, W, 32, 64), {16384, 16384, 4096});  // R >= 0.35: low variance
      for (int r = 0; r < H; ++r)
        for (int c = 0; c < W; ++c) {
          const glm::dvec3 ref = reference_integral(pr::BrdfParams{bc, R, M}, ns[r * W + c], -pixel_dir(r, c, H, W), false);
          for (int k = 0; k < 3; ++k) {
            const double got = out.image[0][k][r][c].item<float>();
            worst = std::max(worst, std::abs(got - ref[k]) / ref[k]);
            EXPECT_TRUE(close_rel(got, ref[k], 0.02)) << "R " << R << " M " << M << ": " << got << " vs " << ref[k];
          }
        }
    }
  }
  std::printf("[ModelRenderLayer] environment 1 + 0.5y + 0.3x: worst relative difference to quadrature %.4f\n", worst);
}

// R = 0: the delta reflection F(NoV) G1(NoV)^2 L(reflect(v, n)), no noise.
TEST(ModelRenderLayer, MirrorBranchIsTheDeltaReflection) {
  const int H = 4, W = 8;
  torch::Tensor normal = torch::zeros({1, 3, H, W});
  std::vector<glm::dvec3> ns;
  for (int r = 0; r < H; ++r)
    for (int c = 0; c < W; ++c) {
      const glm::dvec3 v = -pixel_dir(r, c, H, W);
      glm::dvec3 t, b;
      basis(v, &t, &b);
      const glm::dvec3 n = glm::normalize(v + 0.4 * t);
      ns.push_back(n);
      for (int k = 0; k < 3; ++k) normal[0][k][r][c] = n[k];
    }
  const auto out = pm::render_layer(normal, torch::ones({1, 3, H, W}), torch::zeros({1, 1, H, W}),
                                    torch::ones({1, 1, H, W}), env_probes(H, W, 64, 128), {4, 4, 4096});
  for (int r = 0; r < H; ++r)
    for (int c = 0; c < W; ++c) {
      const glm::dvec3 v = -pixel_dir(r, c, H, W), n = ns[r * W + c];
      const double NoV = glm::dot(n, v);
      const glm::dvec3 l = 2.0 * NoV * n - v;
      const double G1 = pr::G1_SmithSchlick(static_cast<float>(NoV), 1.0f / 8.0f);
      const double F = pr::F_SchlickSG(glm::vec3(1.0f), static_cast<float>(NoV)).x;
      EXPECT_NEAR(out.diffuse[0][0][r][c].item<float>(), 0.0, 1e-7);
      EXPECT_NEAR(out.image[0][0][r][c].item<float>(), F * G1 * G1 * env(l), 0.01 * env(l));
    }
}

// No NaN or Inf in outputs or gradients: R = 0 (and around the mirror threshold), M = 0 and 1,
// grazing and back-facing normals, normals along +-Y (the mapping's poles), zero probes.
TEST(ModelRenderLayer, FiniteOutputsAndGradientsInExtremeCases) {
  const int H = 4, W = 8;
  torch::manual_seed(9);
  const auto dirs = pm::pixel_directions(H, W, torch::TensorOptions());
  const torch::Tensor v = -dirs.permute({2, 0, 1}).unsqueeze(0);  // [1,3,H,W]
  std::vector<torch::Tensor> normals = {
      v.clone(),                                                            // facing the camera
      torch::tensor({0.0f, 1.0f, 0.0f}).view({1, 3, 1, 1}).expand({1, 3, H, W}).clone(),   // +Y
      torch::tensor({0.0f, -1.0f, 0.0f}).view({1, 3, 1, 1}).expand({1, 3, H, W}).clone(),  // -Y
      torch::cross(v, torch::tensor({0.0f, 1.0f, 0.3f}).view({1, 3, 1, 1}).expand({1, 3, H, W}), 1),  // grazing
      -v.clone(),                                                            // back-facing
  };
  for (const float R : {0.0f, 1e-4f, 0.0079f, 0.008f, 0.01f, 0.5f, 1.0f})
    for (const float M : {0.0f, 1.0f})
      for (size_t ni = 0; ni < normals.size(); ++ni)
        for (const bool zero_probes : {false, true}) {
          torch::Tensor n = normals[ni].clone().set_requires_grad(true);
          torch::Tensor base = torch::full({1, 3, H, W}, 0.7f).set_requires_grad(true);
          torch::Tensor rough = torch::full({1, 1, H, W}, R).set_requires_grad(true);
          torch::Tensor metal = torch::full({1, 1, H, W}, M).set_requires_grad(true);
          torch::Tensor probes = (zero_probes ? torch::zeros({1, H, W, 4, 8, 3}) : torch::rand({1, H, W, 4, 8, 3}) * 5.0)
                                     .set_requires_grad(true);
          const auto out = pm::render_layer(n, base, rough, metal, probes, {8, 8, 4096});
          ASSERT_TRUE(torch::isfinite(out.image).all().item<bool>()) << "R " << R << " M " << M << " normal " << ni;
          out.image.sum().backward();
          for (const torch::Tensor* t : {&n, &base, &rough, &metal, &probes})
            ASSERT_TRUE(torch::isfinite(t->grad()).all().item<bool>())
                << "gradient, R " << R << " M " << M << " normal " << ni << " zero probes " << zero_probes;
          if (ni == 4) {
            EXPECT_EQ(out.image.abs().max().item<float>(), 0.0f);  // seen from below: black
          }
        }
}

// Autograd against central finite differences (double, fixed random samples via the seed).
TEST(ModelRenderLayer, GradientsMatchFiniteDifferences) {
  const int H = 2, W = 4;
  auto opts = torch::TensorOptions().dtype(torch::kDouble);
  torch::manual_seed(1);
  const torch::Tensor normal = torch::nn::functional::normalize(
      -pm::pixel_directions(H, W, opts).permute({2, 0, 1}).unsqueeze(0) + 0.3 * torch::rand({1, 3, H, W}, opts),
      torch::nn::functional::NormalizeFuncOptions().dim(1));
  torch::Tensor base = torch::rand({1, 3, H, W}, opts).set_requires_grad(true);
  torch::Tensor rough = (0.3 + 0.5 * torch::rand({1, 1, H, W}, opts)).set_requires_grad(true);
  torch::Tensor metal = torch::rand({1, 1, H, W}, opts).set_requires_grad(true);
  torch::Tensor probes = (torch::rand({1, H, W, 4, 8, 3}, opts) + 0.1).set_requires_grad(true);
  const torch::Tensor weights = torch::rand({1, 3, H, W}, opts);
  auto f = [&]() {
    torch::manual_seed(42);
    return (pm::render_layer(normal, base, rough, metal, probes, {16, 16, 4096}).image * weights).sum();
  };
  f().backward();
  const double h = 1e-6;
  for (torch::Tensor* t : {&base, &metal, &probes}) {
    const torch::Tensor g = t->grad().clone();
    torch::Tensor flat = t->detach().view(-1);
    for (int64_t i = 0; i < flat.numel(); i += std::max<int64_t>(1, flat.numel() / 12)) {
      const double x0 = flat[i].item<double>();
      double fp, fm;
      {
        torch::NoGradGuard ng;
        flat[i] = x0 + h;
        fp = f().item<double>();
        flat[i] = x0 - h;
        fm = f().item<double>();
        flat[i] = x0;
      }
      const double fd = (fp - fm) / (2 * h);
      EXPECT_NEAR(g.view(-1)[i].item<double>(), fd, 1e-6 + 1e-5 * std::abs(fd));
    }
  }
}

// With the renderer's own ground truth (maps and probes of `phyir render --probes`) the
// rendering layer reproduces color.exr up to noise (path tracing, probe and layer Monte
// Carlo), probe resolution and placement: a bound on the relative MSE and on the mean.
// `scene` is a glTF path, or empty for a generated mini room.
pm_check::RenderCheckResult check_on_ground_truth(const std::string& tag, const std::string& scene,
                                                  const std::string& extra_flags = "") {
  const std::filesystem::path bin = PHYIR_BINARY;
  const auto dir = std::filesystem::temp_directory_path() / ("phyir_model_gt_" + tag + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  const std::string q = " > " + (dir / "log.txt").string() + " 2>&1";
  std::filesystem::create_directories(dir);
  std::string gltf = scene;
  if (gltf.empty()) {
    EXPECT_EQ(std::system((bin.string() + " scenes generate --out " + (dir / "rooms").string() +
                           " --count 1 --seed 3 --preset mini" + q).c_str()), 0);
    gltf = (dir / "rooms" / "room_0.gltf").string();
  }
  // Tiny but complete: 64x32 colour, a 16x32 grid of 8x16 probes (cheap cache settings).
  EXPECT_EQ(std::system((bin.string() + " render " + gltf + " --out " + (dir / "view").string() +
                         " --width 64 --height 32 --spp 32 --threads 1 --probes --probe-grid 16x32 "
                         "--probe-res 8x16 --probe-spp 2 --probe-cache-spp 16 --quiet " + extra_flags + q).c_str()), 0);
  pm_check::RenderCheckOptions o;
  o.view_dir = (dir / "view").string();
  const pm_check::RenderCheckResult r = pm_check::check_render_layer(o);
  std::printf("[ModelRenderLayer] %s %s: ground truth %dx%d (%lld pixels): MSE %.5f, relative MSE %.4f, mean colour "
              "%.4f, mean re-render %.4f, mean abs error %.4f\n", tag.c_str(), extra_flags.c_str(), r.width, r.height,
              static_cast<long long>(r.pixels), r.mse, r.relative_mse, r.mean_color, r.mean_rerender, r.mean_abs_error);
  std::filesystem::remove_all(dir);
  return r;
}

TEST(ModelRenderLayer, ReproducesTheRendererOnGroundTruth) {
  if (!std::filesystem::is_regular_file(PHYIR_BINARY)) GTEST_SKIP() << PHYIR_BINARY << " not built";
  const pm_check::RenderCheckResult r = check_on_ground_truth("mini", "");
  EXPECT_GT(r.pixels, 400);
  EXPECT_LT(r.relative_mse, 0.15);
  EXPECT_NEAR(r.mean_rerender / r.mean_color, 1.0, 0.2);
}

// A room lit by punctual lights only (the Blender-exported lit room: a point light, a spot
// and the sun through a window): their light reaches the pixels through the probe texels that hold them
// (docs/probes.md, "What a texel is"). Without those texels the re-render falls to about 0.65
// of color.exr here (0.46 in a lamp-lit night apartment); with them it matches.
TEST(ModelRenderLayer, ReproducesTheRendererUnderPunctualLights) {
  if (!std::filesystem::is_regular_file(PHYIR_BINARY)) GTEST_SKIP() << PHYIR_BINARY << " not built";
  const std::string scene = std::string(PHYIR_SOURCE_ROOT) + "/tests/data/gltf/blender_lit_room/lit_room.gltf";
  const pm_check::RenderCheckResult with = check_on_ground_truth("lit", scene);
  EXPECT_GT(with.pixels, 400);
  EXPECT_LT(with.relative_mse, 0.15);
  EXPECT_NEAR(with.mean_rerender / with.mean_color, 1.0, 0.1);
  // The check can fail: the same view without the lights' texels misses by far more.
  const pm_check::RenderCheckResult without = check_on_ground_truth("lit", scene, "--no-probe-punctual-lights");
  EXPECT_LT(without.mean_rerender / without.mean_color, 0.85);
}
