// Where `phyir bench insert` puts its objects: horizontal, flat, visible surface points of the
// view with room for the object (no triangle of the scene within its box), one per kind:
//   floor   the floor point nearest 2 m from the camera;
//   table   a raised horizontal surface (a table, a box top) nearest 1.5 m;
//   lamp    the horizontal point nearest a lit emitter (an emissive mesh's centre, a point or
//           spot light);
//   window  the horizontal point nearest a window (a light portal's centre).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>

#include "phyir/insert/insert_bench.h"
#include "phyir/core/error.h"

namespace phyir::insert {

namespace {

// Whether the 7x7 pixels around (x, y) are all one horizontal surface at one height (not an edge).
bool flat_around(const InsertView& v, int x, int y, float height) {
  for (int dy = -3; dy <= 3; ++dy)
    for (int dx = -3; dx <= 3; ++dx) {
      const int px = (x + dx + v.width()) % v.width(), py = y + dy;
      if (py < 0 || py >= v.height() || !(v.depth.at(px, py) > 0.0f) || v.normal.at(px, py, 1) < 0.95f) return false;
      if (std::abs(surface_at(v, px, py).position.y - height) > 0.01f) return false;
    }
  return true;
}

struct Candidate {
  int x, y;
  glm::vec3 p;
};

// Every horizontal pixel below the horizon, with its world point.
std::vector<Candidate> horizontal_pixels(const InsertView& v) {
  std::vector<Candidate> out;
  for (int y = v.height() / 2; y < v.height(); ++y)
    for (int x = 0; x < v.width(); ++x)
      if (v.depth.at(x, y) > 0.0f && v.normal.at(x, y, 1) > 0.95f) out.push_back({x, y, surface_at(v, x, y).position});
  return out;
}

struct Lamp {
  glm::vec3 position;
  std::string name;
};

std::vector<Lamp> lit_emitters(const scenes::Scene& scene) {
  std::vector<Lamp> out;
  for (const scenes::Mesh& m : scene.meshes) {
    if (!scene.materials[size_t(m.material)].is_emissive() || m.positions.empty()) continue;
    scenes::Bounds b;
    for (const glm::vec3& p : m.positions) b.extend(p);
    out.push_back({0.5f * (b.min + b.max), m.name});
  }
  for (const scenes::PunctualLight& l : scene.lights)
    if (l.type != scenes::PunctualLight::Type::Directional) out.push_back({l.position, l.name});
  return out;
}

std::vector<Lamp> windows(const scenes::Scene& scene) {
  std::vector<Lamp> out;
  for (size_t k = 0; k < scene.portals.size(); ++k) {
    const scenes::Portal& w = scene.portals[k];
    out.push_back({w.corner + 0.5f * (w.edge_u + w.edge_v), fmt::format("portal {}", k)});
  }
  return out;
}

// The candidate of least `score` that is flat and has room for the object; x = -1 for none.
BenchPlacement best(const InsertView& v, const scenes::Scene& scene, std::vector<Candidate> candidates,
                    const std::function<float(const Candidate&)>& score, float half_width, float height) {
  std::vector<std::pair<float, size_t>> order;
  for (size_t k = 0; k < candidates.size(); ++k) {
    const float s = score(candidates[k]);
    if (std::isfinite(s)) order.push_back({s, k});
  }
  std::sort(order.begin(), order.end());
  for (const auto& [s, k] : order) {
    const Candidate& c = candidates[k];
    if (flat_around(v, c.x, c.y, c.p.y) && clear_of_scene(scene, c.p, half_width, height)) return {"", c.x, c.y, ""};
  }
  return {};
}

// The nearest of `lamps` to p, and its distance.
std::pair<const Lamp*, float> nearest(const std::vector<Lamp>& lamps, const glm::vec3& p) {
  const Lamp* pick = nullptr;
  float d = std::numeric_limits<float>::infinity();
  for (const Lamp& l : lamps)
    if (glm::length(l.position - p) < d) d = glm::length(l.position - p), pick = &l;
  return {pick, d};
}

}  // namespace

bool clear_of_scene(const scenes::Scene& scene, const glm::vec3& p, float half_width, float height) {
  // The box starts 5 mm above the support point, so the surface it stands on does not count.
  const glm::vec3 lo(p.x - half_width, p.y + 0.005f, p.z - half_width), hi(p.x + half_width, p.y + height, p.z + half_width);
  auto overlaps = [&](const glm::vec3& a, const glm::vec3& b) { return glm::all(glm::lessThanEqual(a, hi)) && glm::all(glm::greaterThanEqual(b, lo)); };
  for (const scenes::Mesh& m : scene.meshes) {
    scenes::Bounds mb;
    for (const glm::vec3& q : m.positions) mb.extend(q);
    if (mb.empty() || !overlaps(mb.min, mb.max)) continue;
    for (const glm::uvec3& t : m.triangles) {
      const glm::vec3 &a = m.positions[t.x], &b = m.positions[t.y], &c = m.positions[t.z];
      if (overlaps(glm::min(a, glm::min(b, c)), glm::max(a, glm::max(b, c)))) return false;
    }
  }
  return true;
}

std::vector<BenchPlacement> find_placements(const InsertView& v, const scenes::Scene& scene, float half_width,
                                            float height, std::vector<std::string>& skipped) {
  const std::vector<Candidate> all = horizontal_pixels(v);
  if (all.empty()) fail("{}: no horizontal surface to place an object on", v.dir.string());
  float floor_y = std::numeric_limits<float>::max();
  for (const Candidate& c : all) floor_y = std::min(floor_y, c.p.y);
  const auto on_floor = [&](const Candidate& c) { return c.p.y < floor_y + 0.02f; };
  const auto raised = [&](const Candidate& c) { return c.p.y > floor_y + 0.3f && c.p.y < v.camera.y - 0.2f; };
  const auto depth = [&](const Candidate& c) { return v.depth.at(c.x, c.y); };
  const float inf = std::numeric_limits<float>::infinity();
  std::vector<BenchPlacement> out;
  auto add = [&](const std::string& name, BenchPlacement p, const std::string& note, const std::string& why_missing) {
    if (p.x < 0) return skipped.push_back(fmt::format("{}: {}", name, why_missing));
    for (const BenchPlacement& q : out)
      if (q.x == p.x && q.y == p.y) return skipped.push_back(fmt::format("{}: the same pixel as the {}", name, q.name));
    p.name = name, p.note = note;
    out.push_back(p);
  };
  add("floor", best(v, scene, all, [&](const Candidate& c) { return on_floor(c) ? std::abs(depth(c) - 2.0f) : inf; }, half_width, height),
      "the floor nearest 2 m away", "no clear flat floor in view");
  add("table", best(v, scene, all, [&](const Candidate& c) { return raised(c) ? std::abs(depth(c) - 1.5f) : inf; }, half_width, height),
      "a raised surface nearest 1.5 m away", "no clear flat raised surface in view");
  for (const auto& [name, sources, what] : {std::tuple{"lamp", lit_emitters(scene), "lit emitter"},
                                            std::tuple{"window", windows(scene), "window (light portal)"}}) {
    if (sources.empty()) {
      skipped.push_back(fmt::format("{}: the scene has no {}", name, what));
      continue;
    }
    const auto& near = sources;  // a structured binding cannot be captured (C++17)
    const BenchPlacement p =
        best(v, scene, all, [&near](const Candidate& c) { return nearest(near, c.p).second; }, half_width, height);
    std::string note;
    if (p.x >= 0) {
      const auto [source, d] = nearest(sources, surface_at(v, p.x, p.y).position);
      note = fmt::format("{:.2f} m from {} {}", d, what, source->name);
    }
    add(name, p, note, fmt::format("no clear flat surface in view near a {}", what));
  }
  return out;
}

}  // namespace phyir::insert
