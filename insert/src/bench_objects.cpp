// The benchmark's objects: the relighting spheres of the paper's Table 10, as eval renders them.
#include "phyir/core/error.h"
#include "phyir/eval/relight.h"
#include "phyir/insert/insert_bench.h"

namespace phyir::insert {

BenchObject sphere_object(const std::string& material_key, float radius) {
  for (const eval::SphereMaterial& m : eval::sphere_materials()) {
    if (m.key != material_key) continue;
    scenes::Scene s = eval::material_sphere(m, radius, 64, 32);
    for (glm::vec3& p : s.meshes[0].positions) p.y += radius;
    s.bounds = s.compute_bounds();
    return {m.key, std::move(s)};
  }
  fail("sphere material {}: not one of diffuse, matte_silver, mirror_silver", material_key);
}

std::vector<BenchObject> table10_spheres(float radius) {
  std::vector<BenchObject> spheres;
  for (const eval::SphereMaterial& m : eval::sphere_materials()) spheres.push_back(sphere_object(m.key, radius));
  return spheres;
}

}  // namespace phyir::insert
