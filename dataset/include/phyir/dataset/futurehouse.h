#pragma once
// FutureHouse interchange (docs/futurehouse.md): `phyir dataset import-futurehouse` turns the
// release's layout (futurehouse_layout.h) into one of our datasets with a manifest, so verify,
// train and eval run on it; `export-futurehouse` writes one of ours in that layout, so code
// written for FutureHouse reads it. Both build their output under OUT.partial and rename it
// to OUT when whole.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "phyir/core/image.h"
#include "phyir/dataset/settings.h"

namespace phyir::dataset {

// Which views come in with probes: FutureHouse's illumination release (KePanoLight V1) holds
// probes for some views only, and our manifest has probes for all views or none.
enum class ImportProbes {
  kAuto,  // probes when every imported view has a light file, else none (said in the log)
  kNone,  // never
  kOnly,  // only the views that have a light file, all with probes
};

struct FutureHouseImportOptions {
  std::filesystem::path src;         // holds KePanoData/ (and KePanoLight/, split.json)
  std::filesystem::path out;         // must not exist
  std::filesystem::path split_file;  // empty: SRC/split.json
  int views_per_scene = 0;           // 0: the smallest count of any plan; plans with fewer are left out
  ImportProbes probes = ImportProbes::kAuto;
  int probe_height = 0, probe_width = 0;  // 0: SRC/phyir/export.json's, else the loader's 16 x 32
  std::string normal_axes;                // empty: SRC/phyir/export.json's, else "x,y,z"
  InputSettings input;                    // how input.png is made from the image
  uint64_t seed = 1;                      // view seeds (exposure jitter only)
  int threads = 0;                        // 0: all cores
  bool progress = true;
};

struct FutureHouseImportSummary {
  size_t plans = 0, views = 0;
  bool probes = false;
  std::vector<std::string> left_out;  // "plan: why", for every plan in split.json not imported
  double normals_facing_camera = 1.0;  // fraction of surface pixels whose normal faces the camera
};

FutureHouseImportSummary import_futurehouse(const FutureHouseImportOptions& options);

enum class ExportProbes {
  kAll,    // <i>_light.exr for every view
  kFirst,  // view 0 of each plan only: what the published KePanoLighting accepts (one file per plan)
  kNone,
};

struct FutureHouseExportOptions {
  std::filesystem::path dataset;  // holds manifest.json
  std::filesystem::path out;      // must not exist
  ExportProbes probes = ExportProbes::kAll;
  std::string normal_axes = "x,y,z";
  int threads = 0;
  bool progress = true;
};

struct FutureHouseExportSummary {
  size_t plans = 0, views = 0, light_files = 0;
};

FutureHouseExportSummary export_futurehouse(const FutureHouseExportOptions& options);

// When the normals of a view face the camera (n . d < 0 for the pixel's direction d), the
// fraction of surface pixels that do: low values mean the normal axes given are wrong. `normal` is
// W x H x 3 in our axes, `geometry` W x H x 1.
struct FacingCount {
  uint64_t facing = 0, surface = 0;
};
FacingCount count_normals_facing_camera(const Image& normal, const Image& geometry);

}  // namespace phyir::dataset
