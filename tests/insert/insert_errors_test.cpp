// Bad input: errors that name the file and the problem.
#include <gtest/gtest.h>

#include "insert_test_view.h"
#include "phyir/core/error.h"
#include "phyir/insert/insert_object.h"

namespace phyir::insert {
namespace {

using namespace testing;

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(InsertErrors, PixelOnNoSurface) {
  const fs::path dir = temp_dir("nosurface");
  write_floor_view(dir, 64, 32, make_probes(8, 16, uniform_light));
  const InsertView view = read_insert_view(dir);
  const std::string e = error_of([&] { surface_at(view, 10, 2); });  // looking up: nothing there
  EXPECT_NE(e.find("on no surface"), std::string::npos) << e;
  EXPECT_NE(error_of([&] { surface_at(view, 64, 20); }).find("outside"), std::string::npos);
  fs::remove_all(dir);
}

TEST(InsertErrors, ProbesThatDoNotMatchTheView) {
  const fs::path dir = temp_dir("mismatch");
  write_floor_view(dir, 64, 32, make_probes(8, 8, uniform_light));  // a square grid for a 2:1 view
  const InsertView view = read_insert_view(dir);
  const std::string e = error_of([&] { read_view_probes(dir, view); });
  EXPECT_NE(e.find("probe_mask.exr"), std::string::npos) << e;
  EXPECT_NE(e.find("does not match"), std::string::npos) << e;
  fs::remove_all(dir);
}

TEST(InsertErrors, MissingMapAndEmptyObject) {
  const fs::path dir = temp_dir("missing");
  write_floor_view(dir, 64, 32, make_probes(8, 16, uniform_light));
  fs::remove(dir / "depth.exr");
  const std::string e = error_of([&] { read_insert_view(dir); });
  EXPECT_NE(e.find("depth.exr"), std::string::npos) << e;
  scenes::Scene empty;
  empty.source = "empty.gltf";
  EXPECT_NE(error_of([&] { place_object(empty, SurfacePoint{}, Placement{}); }).find("empty.gltf"),
            std::string::npos);
  EXPECT_NE(error_of([&] {
              LightingRequest l;
              l.source = "no-such-file.exr";
              make_lighting(l, InsertView{}, 0, 0);
            }).find("no-such-file.exr"),
            std::string::npos);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace phyir::insert
