// The files of an insertion (insert_object.h): each written under a temporary name and
// renamed, insert.json last so a folder with it is whole.
#include <filesystem>

#include "phyir/core/atomic_file.h"
#include "phyir/core/colour.h"
#include "phyir/core/image_io.h"
#include "phyir/insert/insert_object.h"

namespace phyir::insert {

namespace fs = std::filesystem;

void write_insert_outputs(const fs::path& out, const InsertView& view, const InsertResult& result) {
  fs::create_directories(out);
  write_image(out / "composite.exr", result.composite.color);
  write_image(out / "composite.png",
              linear_to_display(result.composite.color, float(view.exposure_stops), view.display_view));
  write_image(out / "mask.png", result.composite.mask);
  nlohmann::json record = result.record;
  record["files"] = {"composite.exr", "composite.png", "mask.png", "insert.json"};
  write_file_atomic(out / "insert.json", record.dump(2) + "\n");
}

}  // namespace phyir::insert
