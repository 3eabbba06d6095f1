// Procedural textures. All patterns are periodic over the image (integer frequencies and
// wrapped noise lattices), so they repeat without seams under glTF's REPEAT wrap mode.
#include "generator/room/room_textures.h"

#include <algorithm>
#include <cmath>

#include "generator/room/room_rng.h"
#include "phyir/core/safe_math.h"

namespace phyir::scenes {

namespace {

using glm::vec3;

int wrap(int i, int period) { return ((i % period) + period) % period; }

// A hash of a lattice point in [0, 1).
float lattice(int ix, int iy, uint64_t seed) {
  const uint64_t key = (static_cast<uint64_t>(static_cast<uint32_t>(ix)) << 32) | static_cast<uint32_t>(iy);
  return static_cast<float>(mix64(seed ^ mix64(key)) >> 40) * 0x1p-24f;
}

// Value noise with a lattice of period_x x period_y cells over (x, y) in cell units.
float value_noise(float x, float y, int period_x, int period_y, uint64_t seed) {
  const float fx = std::floor(x), fy = std::floor(y);
  const int ix = static_cast<int>(fx), iy = static_cast<int>(fy);
  const float tx = x - fx, ty = y - fy;
  const float sx = tx * tx * (3.0f - 2.0f * tx), sy = ty * ty * (3.0f - 2.0f * ty);  // smoothstep
  auto at = [&](int dx, int dy) { return lattice(wrap(ix + dx, period_x), wrap(iy + dy, period_y), seed); };
  const float top = at(0, 0) + sx * (at(1, 0) - at(0, 0));
  const float bottom = at(0, 1) + sx * (at(1, 1) - at(0, 1));
  return top + sy * (bottom - top);
}

// Three octaves over u, v in [0, 1), base frequencies fu x fv cells: periodic in u and v.
float fbm(float u, float v, int fu, int fv, uint64_t seed) {
  float sum = 0.0f, amplitude = 0.5f, norm = 0.0f;
  for (int octave = 0; octave < 3; ++octave) {
    const int scale = 1 << octave;
    sum += amplitude * value_noise(u * static_cast<float>(fu * scale), v * static_cast<float>(fv * scale),
                                   fu * scale, fv * scale, seed + static_cast<uint64_t>(octave));
    norm += amplitude;
    amplitude *= 0.5f;
  }
  return sum / norm;
}

vec3 wood(const TextureSpec& t, float u, float v, float pixel) {
  constexpr int kRows = 8;  // planks across the image
  const float row_f = v * kRows;
  const int row = std::min(static_cast<int>(row_f), kRows - 1);
  // Two planks per row, their joints staggered from row to row.
  const float joint = lattice(row, 0, t.seed);
  const float along = u - joint - std::floor(u - joint);  // [0, 1) from the row's first joint
  const int plank = along < 0.5f ? 0 : 1;
  const float tone = lattice(row, plank + 1, t.seed);
  const float grain = 0.5f + 0.5f * std::sin(kTwoPi * (v * kRows * 5.0f + 1.5f * fbm(u, v, 3, kRows, t.seed + 7)));
  const float fine = fbm(u, v, 32, 4 * kRows, t.seed + 13);
  float mix = std::clamp(0.35f * tone + 0.45f * grain + 0.2f * fine, 0.0f, 1.0f);
  vec3 colour = t.colour_a + mix * (t.colour_b - t.colour_a);
  // Dark joints about 1.5 texels wide between rows and plank ends.
  const float row_edge = std::min(row_f - std::floor(row_f), std::ceil(row_f) - row_f) / kRows;
  const float end_edge = std::min({along, std::abs(along - 0.5f), 1.0f - along});
  if (std::min(row_edge, end_edge) < 1.5f * pixel) colour *= 0.45f;
  return colour;
}

vec3 checker(const TextureSpec& t, float u, float v) {
  constexpr int kSquares = 8;
  const int cell = static_cast<int>(u * kSquares) + static_cast<int>(v * kSquares);
  const float noise = 0.95f + 0.05f * fbm(u, v, 16, 16, t.seed);
  return (cell % 2 == 0 ? t.colour_a : t.colour_b) * noise;
}

vec3 tiles(const TextureSpec& t, float u, float v) {
  constexpr int kTiles = 4;
  constexpr float kGrout = 0.03f;  // grout width as a fraction of a tile
  const float x = u * kTiles, y = v * kTiles;
  const float fx = x - std::floor(x), fy = y - std::floor(y);
  if (std::min({fx, 1.0f - fx, fy, 1.0f - fy}) < 0.5f * kGrout) return t.colour_b;
  const float tone = 0.92f + 0.08f * lattice(static_cast<int>(x), static_cast<int>(y), t.seed);
  return t.colour_a * tone * (0.97f + 0.03f * fbm(u, v, 16, 16, t.seed + 3));
}

// Brushed metal (roughness 0.15-0.35, streaks along u) with patches of oxidation (a rough
// dielectric: roughness 0.75, metalness 0): the spatially varying roughness and metalness
// that the network has to recover.
vec3 worn_metal(const TextureSpec& t, float u, float v) {
  const float brushed = fbm(u, v, 2, 64, t.seed);
  const float patches = fbm(u, v, 4, 4, t.seed + 5);
  const float oxide = std::clamp((patches - 0.58f) / 0.06f, 0.0f, 1.0f);  // 6% soft edge
  const float roughness = (0.15f + 0.2f * brushed) * (1.0f - oxide) + 0.75f * oxide;
  return {1.0f, roughness, 1.0f - oxide};
}

}  // namespace

Image render_texture(const TextureSpec& spec) {
  const int n = spec.size;
  Image image(n, n, 3);
  const float pixel = 1.0f / static_cast<float>(n);
  for (int y = 0; y < n; ++y) {
    for (int x = 0; x < n; ++x) {
      const float u = (static_cast<float>(x) + 0.5f) * pixel, v = (static_cast<float>(y) + 0.5f) * pixel;
      vec3 c;
      switch (spec.pattern) {
        case TexturePattern::WoodPlanks: c = wood(spec, u, v, pixel); break;
        case TexturePattern::Checker: c = checker(spec, u, v); break;
        case TexturePattern::Tiles: c = tiles(spec, u, v); break;
        case TexturePattern::WornMetal: c = worn_metal(spec, u, v); break;
      }
      for (int ch = 0; ch < 3; ++ch) image.at(x, y, ch) = clamp01(c[ch]);
    }
  }
  return image;
}

}  // namespace phyir::scenes
